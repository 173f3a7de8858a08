# `run --force` and `dem --force` with a job that cannot run (a malformed packing, a dt above the
# stability limit) exit 2 and leave the results already in the directory byte-identical: nothing
# is written until everything that can be checked has been checked (issue 13, class 4).
# Usage: cmake -DEXE -DDIR -P ... (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/out")
foreach(f job.toml job.resolved.toml log.txt results.h5 means.csv)
  file(WRITE "${DIR}/out/${f}" "earlier run: ${f}\n")
endforeach()
snapshot("${DIR}/out" before)
set(bad "${CMAKE_CURRENT_LIST_DIR}/../jobs/invalid/packings/nan_radius.txt")
get_filename_component(bad "${bad}" ABSOLUTE)

# Coupled job with a packing whose line 7 has a nan radius.
file(READ jobs/triaxial_mpmxdem_small.toml text)
string(REGEX REPLACE "spheres = 100\npsd_diameters = [^\n]*\npsd_passing = [^\n]*\n" "packing = \"${bad}\"\n" text "${text}")
file(WRITE "${DIR}/coupled_bad_packing.toml" "${text}")
execute_process(COMMAND "${EXE}" run "${DIR}/coupled_bad_packing.toml" --out "${DIR}/out" --force
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 "nan_radius.txt:7: 'nan' is not a finite number")
expect_unchanged("${DIR}/out" "${before}" "run --force with a malformed packing")

# Pure DEM job with the same packing.
file(READ jobs/triaxial_dem_small.toml text)
string(REGEX REPLACE "spheres = [0-9]+\npsd_diameters = [^\n]*\npsd_passing = [^\n]*\n" "packing = \"${bad}\"\n" text "${text}")
file(WRITE "${DIR}/dem_bad_packing.toml" "${text}")
execute_process(COMMAND "${EXE}" dem "${DIR}/dem_bad_packing.toml" --out "${DIR}/out" --force
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 "nan_radius.txt:7: 'nan' is not a finite number")
expect_unchanged("${DIR}/out" "${before}" "dem --force with a malformed packing")

# `check` reads the packing too.
execute_process(COMMAND "${EXE}" check "${DIR}/coupled_bad_packing.toml" RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "nan_radius.txt:7:")

# A fixed dt 25 times the stability limit of the elastic job: an input error naming mpm.dt.
file(READ jobs/elastic_triaxial.toml text)
string(REPLACE "end_time = \"2 s\"" "end_time = \"2 s\"\ndt = \"0.1 s\"" text "${text}")
file(WRITE "${DIR}/elastic_big_dt.toml" "${text}")
execute_process(COMMAND "${EXE}" run "${DIR}/elastic_big_dt.toml" --out "${DIR}/out" --force
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "elastic_big_dt.toml:11: mpm.dt = \"0.1 s\": above the stability limit h / c")
expect_unchanged("${DIR}/out" "${before}" "run --force with a dt above the stability limit")
