# Runs `mpiexec -n NP mpmxdem run JOB --out DIR` (a column released by a gate), then
# check_column_collapse.py on the results with ARGS (exit 77 without h5py: skipped).
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
mpmxdem_run(${NP} "${JOB}" --out "${DIR}")
execute_process(COMMAND "${PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check_column_collapse.py" "${DIR}" ${ARGS}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(rc EQUAL 77)
  message("SKIPPED: h5py missing")
  return()
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "check_column_collapse.py failed (${rc})")
endif()
