# A second run into an output directory that a live process holds is refused with exit 2, naming
# the holder from the lock file; once the holder has ended, the lock is taken over (issue 13,
# class 10). `flock` (util-linux) plays the live run. Usage: cmake -DEXE -DFLOCK -DDIR -P ...
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}/out")
file(WRITE "${DIR}/out/mpmxdem.lock" "pid 4242 host other-node since 2026-11-23T00:00:00Z\n")
file(WRITE "${DIR}/out/results.h5" "the live run's results\n")
snapshot("${DIR}/out" before)
execute_process(COMMAND "${FLOCK}" "${DIR}/out/mpmxdem.lock" sleep 6
                COMMAND sh -c "sleep 2; exec \"$0\" run jobs/elastic_triaxial.toml --out \"$1\" --force --max-steps 2" "${EXE}" "${DIR}/out"
                RESULTS_VARIABLE rcs ERROR_VARIABLE err TIMEOUT 60)
list(GET rcs 1 rc)
expect_failure("${rc}" "${err}" 2 "output directory '${DIR}/out' is in use by a running mpmxdem"
               "pid 4242 host other-node")
expect_unchanged("${DIR}/out" "${before}" "a run refused by the lock")
# The holder has ended: the lock is free, the run takes it and writes its own pid.
execute_process(COMMAND "${EXE}" run jobs/elastic_triaxial.toml --out "${DIR}/out" --force --max-steps 2
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 0)
file(READ "${DIR}/out/mpmxdem.lock" lock)
if(NOT lock MATCHES "^pid [0-9]+ host .* since ")
  message(FATAL_ERROR "lock file not rewritten by the run: ${lock}")
endif()
