# Runs `mpiexec -n NP mpmxdem run JOB --out DIR`, then `PYTHON CHECK DIR` (exit 77: skipped).
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
mpmxdem_run(${NP} "${JOB}" --out "${DIR}")
mpmxdem_check("${CHECK}" "${DIR}")
