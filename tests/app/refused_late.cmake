# A run refused after its output directory was opened (an input error found late: exit 2) leaves
# nothing behind: a directory it created is removed, an existing one is left as it was (entries
# it added removed, log.txt cut back, the bytes of the lock file and job files restored), on a
# fresh run and on a restart. The late error is provoked with MPMXDEM_FARM_FAULT (read when the farm starts).
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")

# 1. A fresh run into a directory (and parent) it creates.
execute_process(COMMAND ${CMAKE_COMMAND} -E env MPMXDEM_FARM_FAULT=bogus
                        "${EXE}" run "${JOB}" --out "${DIR}/new/out" --max-steps 1
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 2 "MPMXDEM_FARM_FAULT (environment) = bogus"
               "nothing written: the output directory '${DIR}/new' this run created was removed")
if(EXISTS "${DIR}/new")
  message(FATAL_ERROR "the refused run left its output directory ${DIR}/new")
endif()

# 2. An existing empty directory stays empty.
file(MAKE_DIRECTORY "${DIR}/empty")
execute_process(COMMAND ${CMAKE_COMMAND} -E env MPMXDEM_FARM_FAULT=bogus
                        "${EXE}" run "${JOB}" --out "${DIR}/empty" --max-steps 1
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 2 "is as it was before this run (removed what it added: job.resolved.toml, job.toml, log.txt, mpmxdem.lock)")
file(GLOB left "${DIR}/empty/*")
if(NOT "${left}" STREQUAL "" OR NOT IS_DIRECTORY "${DIR}/empty")
  message(FATAL_ERROR "the refused run changed the empty directory: ${left}")
endif()

# 3. A refused restart leaves the earlier run's directory bit for bit as it was.
execute_process(COMMAND "${EXE}" run "${JOB}" --out "${DIR}/done" --max-steps 2
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the first run failed (rc ${rc}): ${err}")
endif()
file(GLOB ckpt "${DIR}/done/checkpoint_*.h5")
list(GET ckpt 0 ckpt)
snapshot("${DIR}/done" before)
# The restart's job differs in a comment only (the same physics): its job.toml would replace
# the earlier one, and must not.
file(READ "${JOB}" text)
file(WRITE "${DIR}/job_commented.toml" "# the same job, another comment\n${text}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env MPMXDEM_FARM_FAULT=bogus
                        "${EXE}" run "${DIR}/job_commented.toml" --out "${DIR}/done" --restart "${ckpt}"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
expect_failure("${rc}" "${err}" 2 "nothing written: '${DIR}/done' is as it was before this run")
expect_unchanged("${DIR}/done" "${before}" "a refused restart")
