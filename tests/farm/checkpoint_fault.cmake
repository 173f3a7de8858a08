# farm.checkpoint_fault.np2: an interrupted checkpoint write (MPI_Abort in the middle, injected by
# MPMXDEM_FARM_FAULT) leaves the previous checkpoint intact; restarting from it gives results
# identical bit for bit to an uninterrupted run.
# Inputs: MPIEXEC, NP_FLAG, JOB (farm_job), WORK (scratch dir).
cmake_policy(SET CMP0012 NEW)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(run ${MPIEXEC} ${NP_FLAG} 2 --bind-to none ${JOB} run)

macro(check_rc what expect_zero)
  if(${expect_zero} AND NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: exit code ${rc}\n${out}\n${err}")
  elseif(NOT ${expect_zero} AND rc EQUAL 0)
    message(FATAL_ERROR "${what}: should have failed\n${out}\n${err}")
  endif()
endmacro()

# 1. Uninterrupted: 12 steps, checkpoints every 4.
execute_process(COMMAND ${run} ${WORK}/straight 12 4 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check_rc("straight run" TRUE)

# 2. The same, dying in the middle of the 2nd checkpoint (step 8).
set(ENV{MPMXDEM_FARM_FAULT} "abort_checkpoint:2")
execute_process(COMMAND ${run} ${WORK}/faulty 12 4 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
unset(ENV{MPMXDEM_FARM_FAULT})
check_rc("faulty run" FALSE)
foreach(f checkpoint_0000000004.h5 checkpoint_0000000008.h5.tmp)
  if(NOT EXISTS ${WORK}/faulty/${f})
    message(FATAL_ERROR "after the interrupted write ${f} should exist")
  endif()
endforeach()
if(EXISTS ${WORK}/faulty/checkpoint_0000000008.h5)
  message(FATAL_ERROR "the interrupted checkpoint must not be published")
endif()

# 3. The previous checkpoint is intact (every checksum verified) ...
execute_process(COMMAND ${JOB} inspect ${WORK}/faulty/checkpoint_0000000004.h5
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check_rc("inspect the previous checkpoint" TRUE)
# ... the half-written one is refused ...
execute_process(COMMAND ${JOB} inspect ${WORK}/faulty/checkpoint_0000000008.h5.tmp
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check_rc("inspect the interrupted checkpoint" FALSE)
# ... and restartable: the finished run equals the uninterrupted one, bit for bit.
execute_process(COMMAND ${run} ${WORK}/faulty 12 4 ${WORK}/faulty/checkpoint_0000000004.h5
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check_rc("restart" TRUE)
execute_process(COMMAND ${JOB} compare ${WORK}/straight/results.h5 ${WORK}/faulty/results.h5
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check_rc("compare straight and restarted results" TRUE)
message(STATUS "interrupted checkpoint: previous one intact, restart identical")
