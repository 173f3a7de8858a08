# A run whose DEM RVEs cannot fit in the memory of its nodes (8192 RVEs of 500,000 spheres: at
# least 4.2 TB) is refused on 2 ranks before any sample is prepared or anything written: exit 2,
# naming the job key, the figures and what to change (docs/reference/errors.md), both into a new directory
# and into an earlier run's, which stays as it was; `check` of the same job says what it needs.
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/biaxial_plane_strain_8x16.toml text)
string(REPLACE "points_per_cell = [2, 1, 2]" "points_per_cell = [8, 1, 8]" text "${text}")
string(REPLACE "spheres = 300" "spheres = 500000" text "${text}")
file(WRITE "${DIR}/huge.toml" "${text}")
# The key's line in the job (its header may grow): the newlines before it, plus one.
string(FIND "${text}" "points_per_cell = [8, 1, 8]" at)
string(SUBSTRING "${text}" 0 ${at} before)
string(REGEX MATCHALL "\n" newlines "${before}")
list(LENGTH newlines line)
math(EXPR line "${line} + 1")
set(fragments "huge.toml:${line}: mpm.body[0].points_per_cell = [8, 1, 8]: the run's 8192 DEM RVEs of 500000 spheres need at least 4.19e+03 GB of memory"
              "rank(s) on the node of rank 0 would hold 8192 of them at the start"
              "use more nodes (ranks on separate nodes), fewer material points or smaller RVEs")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/huge.toml" --out "${DIR}/new"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 ${fragments})
if(EXISTS "${DIR}/new")
  message(FATAL_ERROR "the refused run left an output directory ${DIR}/new")
endif()
string(FIND "${err}" "spheres generated" pos)
if(NOT pos EQUAL -1)
  message(FATAL_ERROR "a sample was prepared before the refusal:\n${err}")
endif()

# An earlier run's directory (with --force) is left byte for byte as it was.
file(MAKE_DIRECTORY "${DIR}/old")
file(WRITE "${DIR}/old/results.h5" "an earlier run's results")
snapshot("${DIR}/old" before)
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/huge.toml" --out "${DIR}/old" --force
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 ${fragments})
expect_unchanged("${DIR}/old" "${before}" "a run refused for its memory")

# `check` (one rank: it does not know the run's nodes) accepts the job and says what it needs.
execute_process(COMMAND "${EXE}" check "${DIR}/huge.toml" RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err
                TIMEOUT 120)
expect_failure("${rc}" "${err}" 0 "8192 DEM RVEs of 500000 spheres: at least 4.19e+03 GB of memory in all")
