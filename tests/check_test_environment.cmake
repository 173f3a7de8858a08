# tests.environment: the environment that tests/CMakeLists.txt gives a GoogleTest executable's
# tests reaches each of them (mpmxdem_gtest sets it from a script CTest reads after the discovered
# tests; given to gtest_discover_tests, only a list's first entry did). Reads `ctest -N -V`.
# Usage: cmake -DCTEST=<ctest> -DBUILD=<build dir> -P check_test_environment.cmake
# ctest -N runs from a scratch directory whose CTestTestfile.cmake includes the build's: run in the
# build directory itself it would rewrite Testing/Temporary/LastTest.log under the running suite.
set(scratch "${BUILD}/tests/environment_check")
file(MAKE_DIRECTORY "${scratch}")
file(WRITE "${scratch}/CTestTestfile.cmake" "subdirs(\"${BUILD}\")\n")

function(expect_environment regex)
  execute_process(COMMAND "${CTEST}" -N -V -R "${regex}" WORKING_DIRECTORY "${scratch}"
                  OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "ctest -N -V -R ${regex} failed (${rc}):\n${out}")
  endif()
  string(REGEX MATCHALL "Test +#[0-9]+:" tests "${out}")
  list(LENGTH tests n)
  if(n EQUAL 0)
    message(FATAL_ERROR "no test matches ${regex}:\n${out}")
  endif()
  foreach(var IN LISTS ARGN)
    string(REGEX MATCHALL "[0-9]+:  ${var}\n" found "${out}")
    list(LENGTH found m)
    if(NOT m EQUAL n)
      message(FATAL_ERROR "${var} reaches ${m} of the ${n} tests matching ${regex}:\n${out}")
    endif()
  endforeach()
  message(STATUS "${regex}: ${n} tests, each with ${ARGN}")
endfunction()

expect_environment([[^dem\.MuOfI\.]] GTEST_COLOR=no OMP_NUM_THREADS=1)
expect_environment([[^dem\.Verification\.]] GTEST_COLOR=no OMP_NUM_THREADS=1)
expect_environment([[^dem\.Simulation\.]] GTEST_COLOR=no)
