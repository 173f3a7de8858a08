# A run that leaves the physics (a platen driven at 1000 m/s crushes the sample within a few
# steps) stops with exit 3 on 2 ranks, naming the step, the simulated time, the point id and the
# value, instead of running on to exit 0 (issue 13, class 6). Usage: cmake -DEXE -DMPIEXEC -DDIR -P
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/elastic_triaxial.toml text)
string(REPLACE "z = \"-1 mm/s\"" "z = \"-1000 m/s\"" text "${text}")
string(REPLACE "damping = 0.2" "damping = 0.2\nmove_points = true" text "${text}")
file(WRITE "${DIR}/crush.toml" "${text}")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/crush.toml" --out "${DIR}/out" --max-steps 200
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 3 "numerical failure: mpm step " " (t = " "point id " "volume")
