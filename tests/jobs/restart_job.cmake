# Restart through the command line, compared with h5diff and no tolerance: A runs STEPS steps on 2
# ranks; B runs STEPS/2 on 3 ranks (checkpoint at the end), then restarts from that checkpoint on 2
# ranks to STEPS. A's and B's results.h5 must be identical. A damaged checkpoint is then refused
# with exit 2 and a message naming the file, and nothing in B changes. Optional COUPLING: lines
# (separated by '|') added to the job's [dem.coupling] table (the edited job is written to
# DIR/job.toml; the job must not name files relative to its own directory).
math(EXPR half "${STEPS} / 2")
file(REMOVE_RECURSE "${DIR}")
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
if(DEFINED COUPLING)
  mpmxdem_job_with("${JOB}" dem.coupling "${COUPLING}" "${DIR}/job.toml")
  set(JOB "${DIR}/job.toml")
endif()
mpmxdem_run(2 "${JOB}" --out "${DIR}/a" --max-steps ${STEPS})
mpmxdem_run(3 "${JOB}" --out "${DIR}/b" --max-steps ${half})
string(LENGTH "${half}" len)
math(EXPR pad "10 - ${len}")
string(REPEAT "0" ${pad} zeros)
set(ckpt "${DIR}/b/checkpoint_${zeros}${half}.h5")
if(NOT EXISTS "${ckpt}")
  message(FATAL_ERROR "no checkpoint ${ckpt}")
endif()
mpmxdem_run(2 "${JOB}" --out "${DIR}/b" --restart "${ckpt}" --max-steps ${STEPS})
execute_process(COMMAND "${H5DIFF}" "${DIR}/a/results.h5" "${DIR}/b/results.h5" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "results of the restarted run differ from the straight run:\n${out}")
endif()
# A truncated checkpoint: refused before anything is written.
file(WRITE "${DIR}/broken.h5" "")
file(SIZE "${DIR}/b/results.h5" size_before)
execute_process(COMMAND "${MPIEXEC}" -n 2 "${EXE}" run "${JOB}" --out "${DIR}/b" --restart "${DIR}/broken.h5"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
file(SIZE "${DIR}/b/results.h5" size_after)
string(FIND "${err}" "broken.h5" pos)
if(NOT rc EQUAL 2 OR pos EQUAL -1 OR NOT size_before EQUAL size_after)
  message(FATAL_ERROR "a broken checkpoint was not refused cleanly (rc ${rc}):\n${err}")
endif()
