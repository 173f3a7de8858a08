# Issue 16's suite check of the plane-strain biaxial: the job JOB (tests/jobs/biaxial_small*.toml) on 2 ranks, then
# tests/jobs/check_biaxial.py (PYTHON) with BAND, R_TOL and BASE_TOL.
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
mpmxdem_run(2 ${JOB} --out "${DIR}")
mpmxdem_check(tests/jobs/check_biaxial.py "${DIR}" ${BAND} ${R_TOL} ${BASE_TOL})
