# `mpirun -np RANKS laguerre run|compare SCENARIO` writes (on rank 0) the results.csv (comparison.csv)
# that the sequential `laguerre run|compare SCENARIO --jobs 1` writes, byte for byte, with the same
# exit status, whichever way the ranks share the work (SPLIT: --mpi-split auto, runs or network).
#   cmake -DLAGUERRE=… -DMPIEXEC=… -DRANKS=2 -DSCENARIO=… -DWORK=dir [-DCMD=compare] [-DSPLIT=runs]
#         -P RunUnderMpi.cmake
if(NOT DEFINED CMD)
  set(CMD run)
endif()
if(NOT DEFINED SPLIT)
  set(SPLIT auto)
endif()
file(REMOVE_RECURSE ${WORK})
if(CMD STREQUAL "compare")
  set(flags --force --no-charts)
  set(table comparison.csv)
  set(banner "scenario [^\n]*run\\(s\\) in")
else()
  set(flags --force --set outputs.pictures=false)
  set(table results.csv)
  set(banner "scenario [^\n]*run\\(s\\)")
endif()
execute_process(COMMAND ${LAGUERRE} ${CMD} ${SCENARIO} -o ${WORK}/sequential --jobs 1 ${flags}
                OUTPUT_QUIET RESULT_VARIABLE sequential_status)
execute_process(COMMAND ${MPIEXEC} -np ${RANKS} --oversubscribe ${LAGUERRE} ${CMD} ${SCENARIO} -o ${WORK}/parallel
                        --mpi-split ${SPLIT} ${flags}
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE parallel_status)
if(NOT sequential_status EQUAL parallel_status)
  message(FATAL_ERROR "exit status ${sequential_status} sequentially, ${parallel_status} on ${RANKS} ranks:\n${out}\n${err}")
endif()
string(REGEX MATCHALL "${banner}" banners "${out}")
list(LENGTH banners printed)
if(NOT printed EQUAL 1)
  message(FATAL_ERROR "expected one summary (rank 0 prints, the others stay quiet), got ${printed}:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/sequential/${table} ${WORK}/parallel/${table}
                RESULT_VARIABLE differ)
if(differ)
  file(READ ${WORK}/sequential/${table} a)
  file(READ ${WORK}/parallel/${table} b)
  message(FATAL_ERROR "${table} differs on ${RANKS} ranks (--mpi-split ${SPLIT}):\n${a}\n---\n${b}")
endif()
message(STATUS "${table} identical on ${RANKS} ranks (--mpi-split ${SPLIT})")
