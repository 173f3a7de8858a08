# Runs `mpiexec -n NP mpmxdem run JOB --out DIR`, checks that the log reports the in-situ
# preparations, then check_geostatic.py on the results (exit 77 without h5py: skipped).
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
mpmxdem_run(${NP} "${JOB}" --out "${DIR}")
file(READ "${DIR}/log.txt" log)
foreach(fragment IN ITEMS "in 8 group(s) of targets" "8 preparation(s)" "in-situ preparation: group")
  string(FIND "${log}" "${fragment}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "log.txt lacks '${fragment}':\n${log}")
  endif()
endforeach()
mpmxdem_check("${CMAKE_CURRENT_LIST_DIR}/check_geostatic.py" "${DIR}" ${ARGS})
