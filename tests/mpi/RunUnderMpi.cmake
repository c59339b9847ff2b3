# `mpirun -np RANKS laguerre run SCENARIO` writes (on rank 0) the results.csv that the sequential
# `laguerre run SCENARIO --jobs 1` writes, byte for byte, with the same exit status.
#   cmake -DLAGUERRE=… -DMPIEXEC=… -DRANKS=2 -DSCENARIO=… -DWORK=dir -P RunUnderMpi.cmake
file(REMOVE_RECURSE ${WORK})
set(flags --force --set outputs.pictures=false)
execute_process(COMMAND ${LAGUERRE} run ${SCENARIO} -o ${WORK}/sequential --jobs 1 ${flags}
                OUTPUT_QUIET RESULT_VARIABLE sequential_status)
execute_process(COMMAND ${MPIEXEC} -np ${RANKS} --oversubscribe ${LAGUERRE} run ${SCENARIO} -o ${WORK}/parallel ${flags}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE parallel_status)
if(NOT sequential_status EQUAL parallel_status)
  message(FATAL_ERROR "exit status ${sequential_status} sequentially, ${parallel_status} on ${RANKS} ranks:\n${out}\n${err}")
endif()
string(REGEX MATCHALL "scenario [^\n]*run\\(s\\)" banners "${out}")
list(LENGTH banners printed)
if(NOT printed EQUAL 1)
  message(FATAL_ERROR "expected one summary (rank 0 prints, the others stay quiet), got ${printed}:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/sequential/results.csv ${WORK}/parallel/results.csv
                RESULT_VARIABLE differ)
if(differ)
  file(READ ${WORK}/sequential/results.csv a)
  file(READ ${WORK}/parallel/results.csv b)
  message(FATAL_ERROR "results.csv differs on ${RANKS} ranks:\n${a}\n---\n${b}")
endif()
message(STATUS "results.csv identical on ${RANKS} ranks")
