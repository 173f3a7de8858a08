# `mpmxdem dem` with a loading that implies more DEM steps than any machine runs (a strain path of
# 1e308 s) is refused naming the key, exit 2, nothing written (a triaxial at an inertial number of
# 1e-30 is refused by the key's range); with --max-steps it runs, writing a row every output.every steps (the step count of
# the strain path was an undefined float-to-int conversion that made every step a row).
# Usage: cmake -DEXE -DJOB=jobs/triaxial_dem_small.toml -DDIR -P ... (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
# Runs `dem JOB --out DIR/NAME`, expects exit 2 with FRAGMENT and no DIR/NAME.
function(expect_refused job name fragment)
  execute_process(COMMAND "${EXE}" dem "${job}" --out "${DIR}/${name}" RESULT_VARIABLE rc ERROR_VARIABLE err)
  expect_failure("${rc}" "${err}" 2 "${fragment}")
  if(EXISTS "${DIR}/${name}")
    message(FATAL_ERROR "the refused run left ${DIR}/${name}")
  endif()
endfunction()
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ "${JOB}" text)
string(REGEX REPLACE "type = \"triaxial\"\ninertial_number = [^\n]*\naxial_strain = [^\n]*\nconfining_pressure = [^\n]*"
       "type = \"strain_path\"\nvelocity_gradient = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.01]\nduration = 1e308"
       path_text "${text}")
string(FIND "${path_text}" "duration = 1e308" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "the [dem.loading] of ${JOB} is not the one this test rewrites")
endif()
file(WRITE "${DIR}/path.toml" "${path_text}")
expect_refused("${DIR}/path.toml" path "dem.loading.duration = 1e+308: implies about inf DEM steps, more than 1e+12")
execute_process(COMMAND "${EXE}" dem "${DIR}/path.toml" --out "${DIR}/bounded" --max-steps 400
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 0)
file(STRINGS "${DIR}/bounded/dem_series.csv" rows)
list(LENGTH rows n)
if(n GREATER 10)
  message(FATAL_ERROR "400 steps at output.every = 200 wrote ${n} lines")
endif()
string(REGEX REPLACE "(\\[dem.loading\\]\ntype = \"triaxial\"\n)inertial_number = [^\n]*" "\\1inertial_number = 1e-30"
       slow_text "${text}")
file(WRITE "${DIR}/slow.toml" "${slow_text}")
# (an inertial number below 1e-6 is refused by its range before anything is prepared)
expect_refused("${DIR}/slow.toml" slow "dem.loading.inertial_number = 1e-30: must be in [1e-06, 1)")
