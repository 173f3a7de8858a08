# mpmxdem_run(<np> <args>...): runs `MPIEXEC -n <np> --bind-to none EXE run <args>...` from a CMake
# script (the caller sets EXE and MPIEXEC); a failure stops the script with the run's output.
function(mpmxdem_run np)
  execute_process(COMMAND "${MPIEXEC}" -n ${np} --bind-to none "${EXE}" run ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mpmxdem run ${ARGN} on ${np} ranks failed (${rc}):\n${out}\n${err}")
  endif()
endfunction()
