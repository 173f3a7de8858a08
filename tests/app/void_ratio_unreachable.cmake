# A target void ratio (dem.preparation.void_ratio) that the preparation cannot reach is refused
# with exit 2 naming the job file, the key's line, its value and why, and leaves nothing behind:
# (1) `dem`, a target looser than the compaction at friction_angle gives; (2) `run` on 2 ranks,
# a target denser than a frictionless compaction makes (every rank agrees on the exit).
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")

# A copy of JOB with `void_ratio = VALUE` as the first key of [dem.preparation].
function(with_void_ratio job value out)
  file(READ "${job}" text)
  string(REPLACE "[dem.preparation]\n" "[dem.preparation]\nvoid_ratio = ${value}\n" text "${text}")
  file(WRITE "${out}" "${text}")
endfunction()

with_void_ratio(jobs/triaxial_dem_small.toml 0.9 "${DIR}/loose.toml")
execute_process(COMMAND "${EXE}" dem "${DIR}/loose.toml" --out "${DIR}/loose"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 2 "loose.toml:25: dem.preparation.void_ratio = 0.9: the compaction at dem.preparation.friction_angle = 1 deg already gives a denser packing")
if(EXISTS "${DIR}/loose")
  message(FATAL_ERROR "the refused dem job left its output directory ${DIR}/loose")
endif()

with_void_ratio(tests/jobs/column_collapse_tiny.toml 0.2 "${DIR}/dense.toml")
execute_process(COMMAND "${MPIEXEC}" -n 2 "${EXE}" run "${DIR}/dense.toml" --out "${DIR}/dense"
                        --max-steps 1
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 2 "dense.toml:23: dem.preparation.void_ratio = 0.2: none of 16 compactions of the cloud between 0 and 1 deg of friction came within dem.preparation.void_ratio_tolerance = 0.003")
if(EXISTS "${DIR}/dense")
  message(FATAL_ERROR "the refused run left its output directory ${DIR}/dense")
endif()
