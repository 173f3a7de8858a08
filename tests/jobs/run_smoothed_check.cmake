# Issue 18's suite check of strain smoothing: the pure DEM of jobs/triaxial_dem_small.toml and the
# smoothed coupled cell of jobs/triaxial_mpmxdem_smoothed_small.toml on the same packing, then
# tests/jobs/check_smoothed.py (PYTHON) on both with BAND, SPREAD and Q_TOL.
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
execute_process(COMMAND "${EXE}" dem jobs/triaxial_dem_small.toml --out "${DIR}/dem"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpmxdem dem jobs/triaxial_dem_small.toml failed (${rc}):\n${err}")
endif()
mpmxdem_run(2 jobs/triaxial_mpmxdem_smoothed_small.toml --out "${DIR}/run")
mpmxdem_check(tests/jobs/check_smoothed.py "${DIR}/run" "${DIR}/dem/dem_series.csv" ${BAND} ${SPREAD} ${Q_TOL})
