# verification.coupled.element_test: runs JOB as a coupled run (`mpiexec -n NP mpmxdem run`) and as
# pure DEM (`mpmxdem dem`, its [dem.loading]) into DIR, then compares the two with COMPARE
# (compare_element_test: q and eps_v against axial strain, tolerances TOL_Q and TOL_EPS_V on
# eps_a in [EPS_FROM, EPS_TO]). Run from the source root.
include(${CMAKE_CURRENT_LIST_DIR}/../jobs/mpmxdem_run.cmake)
file(REMOVE_RECURSE "${DIR}")
mpmxdem_run(${NP} "${JOB}" --out "${DIR}/coupled")
execute_process(COMMAND "${EXE}" dem "${JOB}" --out "${DIR}/dem" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpmxdem dem failed (${rc}):\n${err}")
endif()
execute_process(COMMAND "${COMPARE}" "${DIR}/coupled/means.csv" "${DIR}/dem/dem_series.csv"
                        ${EPS_FROM} ${EPS_TO} ${TOL_Q} ${TOL_EPS_V}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the coupled element test does not reproduce pure DEM (exit ${rc})")
endif()
