# An output directory that cannot be created (its parent is a file) must end `run` and `dem` on 2
# ranks with exit 2 and the reason, on every rank, in seconds: no rank may go on into the farm's
# collectives and hang (issue 13, class 1). Usage: cmake -DEXE -DMPIEXEC -DDIR -P ...
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(WRITE "${DIR}/afile" "x\n")
foreach(cmd_job IN ITEMS "run;jobs/triaxial_mpmxdem_small.toml" "dem;jobs/triaxial_dem_small.toml"
                          "run;jobs/elastic_triaxial.toml")
  list(GET cmd_job 0 cmd)
  list(GET cmd_job 1 job)
  execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" ${cmd} ${job} --out "${DIR}/afile/sub"
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
  expect_failure("${rc}" "${err}" 2 "cannot create output directory '${DIR}/afile/sub'"
                 "is not a directory")
endforeach()
# A directory without write permission (not as root: root writes anywhere).
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT uid STREQUAL "0")
  file(MAKE_DIRECTORY "${DIR}/ro")
  file(CHMOD "${DIR}/ro" PERMISSIONS OWNER_READ OWNER_EXECUTE)
  execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run jobs/elastic_triaxial.toml --out "${DIR}/ro/sub"
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
  file(CHMOD "${DIR}/ro" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)
  expect_failure("${rc}" "${err}" 2 "cannot create output directory")
endif()
# More ranks than RVEs: accepted with a warning (the idle ranks wait), not in silence.
file(READ jobs/elastic_triaxial.toml text)
string(REPLACE "points_per_cell = 2" "points_per_cell = 1" text "${text}")
file(WRITE "${DIR}/one_rve.toml" "${text}")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/one_rve.toml" --out "${DIR}/one_rve" --max-steps 2
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 0 "warning: 2 ranks for 1 RVE(s): 1 rank(s) will hold no RVE and only wait")
