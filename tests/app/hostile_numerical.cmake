# A run that leaves the physics (a platen driven at 150 m/s, below the wave speed of 199 m/s that
# the input rules allow: a platen at 1000 m/s is now an input error, exit 2) squeezes the sample
# out of its one-cell grid within a few steps and stops with exit 3 on 2 ranks, naming the step,
# the simulated time, the point id and its position, instead of running on to exit 0 (issue 13,
# class 6; the volume guard is unit-tested, mpm.Solver). Usage: cmake -DEXE -DMPIEXEC -DDIR -P
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/elastic_triaxial.toml text)
string(REPLACE "z = \"-1 mm/s\"" "z = \"-150 m/s\"" text "${text}")
string(REPLACE "damping = 0.2" "damping = 0.2\nmove_points = true" text "${text}")
file(WRITE "${DIR}/crush.toml" "${text}")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/crush.toml" --out "${DIR}/out" --max-steps 200
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 3 "numerical failure: mpm step " " (t = " "point id " "has left the grid")

# The platen at 1000 m/s, faster than the material's waves (c = 199 m/s): refused before anything
# is written, naming the key (exit 2).
string(REPLACE "z = \"-150 m/s\"" "z = \"-1000 m/s\"" fast "${text}")
file(WRITE "${DIR}/shock.toml" "${fast}")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/shock.toml" --out "${DIR}/shock" --max-steps 200
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 "shock.toml:36: mpm.velocity[1].z = \"-1000 m/s\": |v| = 1000 m/s is not below the largest wave speed of the materials, c = 199.2 m/s")
if(EXISTS "${DIR}/shock")
  message(FATAL_ERROR "the refused run wrote ${DIR}/shock")
endif()

# The failed run's run_summary.json (docs/reference/outputs.md) says how it ended, with the message.
file(READ "${DIR}/out/run_summary.json" summary)
string(JSON ended GET "${summary}" ended)
string(JSON code GET "${summary}" exit_code)
string(JSON error GET "${summary}" error)
if(NOT ended STREQUAL "numerical_failure" OR NOT code EQUAL 3 OR NOT error MATCHES "point id .* has left the grid")
  message(FATAL_ERROR "run_summary.json of the failed run: ended ${ended}, exit_code ${code}, error '${error}'")
endif()
message(STATUS "run_summary.json: ended ${ended}, exit_code ${code}")
