# Runs `mpiexec -n NP mpmxdem run JOB --out DIR` (a column released by a gate), then
# check_column_collapse.py on the results with ARGS (exit 77 without h5py: skipped). Optional MPM
# and COUPLING: lines (separated by '|') added to the job's [mpm] and [dem.coupling] tables (the
# edited job is written to DIR.job.toml).
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
if(DEFINED MPM)
  mpmxdem_job_with("${JOB}" mpm "${MPM}" "${DIR}.job.toml")
  set(JOB "${DIR}.job.toml")
endif()
if(DEFINED COUPLING)
  mpmxdem_job_with("${JOB}" dem.coupling "${COUPLING}" "${DIR}.job.toml")
  set(JOB "${DIR}.job.toml")
endif()
mpmxdem_run(${NP} "${JOB}" --out "${DIR}")
mpmxdem_check("${CMAKE_CURRENT_LIST_DIR}/check_column_collapse.py" "${DIR}" ${ARGS})
