# Runs `mpiexec -n NP mpmxdem run JOB --out DIR` (a column released by a gate), then
# check_column_collapse.py on the results with ARGS (exit 77 without h5py: skipped). Optional MPM:
# lines (separated by '|') added to the job's [mpm] table (the edited job is written to
# DIR.job.toml).
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
if(DEFINED MPM)
  file(READ "${JOB}" text)
  string(FIND "${text}" "\n[mpm]\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${JOB} has no [mpm] table to add '${MPM}' to")
  endif()
  string(REPLACE "|" "\n" lines "${MPM}")
  string(REPLACE "\n[mpm]\n" "\n[mpm]\n${lines}\n" text "${text}")
  file(WRITE "${DIR}.job.toml" "${text}")
  set(JOB "${DIR}.job.toml")
endif()
mpmxdem_run(${NP} "${JOB}" --out "${DIR}")
mpmxdem_check("${CMAKE_CURRENT_LIST_DIR}/check_column_collapse.py" "${DIR}" ${ARGS})
