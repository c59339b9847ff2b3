# `mpirun -np RANKS laguerre simulate GRAPH OPTIONS…` prints, on rank 0 only, the JSON document the
# sequential run prints, but for the three wall-clock fields (wall_seconds, events_per_second,
# peak_memory_bytes) and mpi_ranks (which must say RANKS: the parallel kernel ran), with the same
# exit status.
#   cmake -DLAGUERRE=… -DMPIEXEC=… -DRANKS=2 -DGRAPH=… -DOPTIONS="a;b" -P SimulateUnderMpi.cmake
function(strip_wall json out)
  foreach(key wall_seconds events_per_second peak_memory_bytes)
    string(JSON json REMOVE "${json}" ${key})
  endforeach()
  set(${out} "${json}" PARENT_SCOPE)
endfunction()
execute_process(COMMAND ${LAGUERRE} simulate ${GRAPH} ${OPTIONS} --json
                OUTPUT_VARIABLE sequential RESULT_VARIABLE sequential_status)
execute_process(COMMAND ${MPIEXEC} -np ${RANKS} --oversubscribe ${LAGUERRE} simulate ${GRAPH} ${OPTIONS} --json
                OUTPUT_VARIABLE parallel ERROR_VARIABLE parallel_err RESULT_VARIABLE parallel_status)
if(NOT sequential_status EQUAL parallel_status)
  message(FATAL_ERROR "exit status ${sequential_status} sequentially, ${parallel_status} on ${RANKS} ranks:\n${parallel_err}")
endif()
string(JSON kind ERROR_VARIABLE not_json TYPE "${parallel}")
if(not_json)
  message(FATAL_ERROR "rank output is not one JSON document (other ranks must stay quiet):\n${parallel}")
endif()
string(JSON ranks ERROR_VARIABLE no_ranks GET "${parallel}" mpi_ranks)
if(NOT ranks EQUAL RANKS)
  message(FATAL_ERROR "the run does not report ${RANKS} MPI ranks (mpi_ranks: ${ranks}${no_ranks})")
endif()
string(JSON parallel REMOVE "${parallel}" mpi_ranks)
strip_wall("${sequential}" a)
strip_wall("${parallel}" b)
if(NOT a STREQUAL b)
  message(FATAL_ERROR "the ${RANKS}-rank run differs from the sequential one:\n${a}\n---\n${b}")
endif()
string(JSON events GET "${sequential}" events)
message(STATUS "identical on ${RANKS} ranks (${events} events)")
