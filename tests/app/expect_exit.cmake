# Runs EXE with the arguments ARGS (a CMake list, may be empty) and passes when it exits with CODE
# and its standard error contains FRAGMENT. Usage:
#   cmake -DEXE=... "-DARGS=a;b" -DCODE=2 "-DFRAGMENT=..." -P expect_exit.cmake
execute_process(COMMAND "${EXE}" ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "${CODE}")
  message(FATAL_ERROR "expected exit code ${CODE}, got '${rc}'\nstdout: ${out}\nstderr: ${err}")
endif()
string(FIND "${err}" "${FRAGMENT}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "expected fragment not found in stderr:\n  ${FRAGMENT}\nstderr was:\n${err}")
endif()
