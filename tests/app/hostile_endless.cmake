# `mpmxdem run` with an end time no machine reaches (1e300 s: about 4e302 MPM steps of the elastic
# triaxial) is refused on 2 ranks naming mpm.end_time, exit 2, nothing written; with --max-steps
# it runs; a restart of it
# without --max-steps is refused from the mean dt of the checkpoint, the directory left as it was.
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/elastic_triaxial.toml text)
string(REPLACE "end_time = \"2 s\"" "end_time = \"1e300 s\"" text "${text}")
file(WRITE "${DIR}/endless.toml" "${text}")
set(refusal "endless.toml:10: mpm.end_time = \"1e300 s\": implies about 3.98e+302 MPM steps, more than 1e+12 (years of computing)")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/endless.toml" --out "${DIR}/out"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 "${refusal}")
if(EXISTS "${DIR}/out")
  message(FATAL_ERROR "the refused run left ${DIR}/out")
endif()
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/endless.toml" --out "${DIR}/out" --max-steps 3
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 0)
snapshot("${DIR}/out" before)
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run "${DIR}/endless.toml" --out "${DIR}/out" --restart latest
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${err}" 2 "mpm.end_time = \"1e300 s\": implies about" "MPM steps, more than 1e+12")
expect_unchanged("${DIR}/out" "${before}" "a restart refused for its end time")
