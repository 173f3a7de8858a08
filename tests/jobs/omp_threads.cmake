# OpenMP threads over RVEs (the farm's loop) and inside them give the results of one thread, bit
# for bit: 64 tiny RVEs (tests/jobs/many_ranks.toml) with OMP_NUM_THREADS = 1 and 2 on one rank,
# and 2 threads on each of 2 ranks. The rest of the suite runs with OMP_NUM_THREADS=1; a DEM
# work-shared loop that bound to the farm's team of 2 threads instead of its own once hung here
# (2026-11-26, never landed). Usage: cmake -DEXE -DMPIEXEC -DH5DIFF -DDIR -P ... (source root)
file(REMOVE_RECURSE "${DIR}")
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
set(job tests/jobs/many_ranks.toml)
foreach(case "1 1" "1 2" "2 2")
  separate_arguments(case)
  list(GET case 0 np)
  list(GET case 1 threads)
  set(ENV{OMP_NUM_THREADS} ${threads})
  mpmxdem_run(${np} ${job} --out "${DIR}/np${np}_t${threads}" --max-steps 10)
  file(STRINGS "${DIR}/np${np}_t${threads}/log.txt" done REGEX "done: 10 MPM steps")
  if(NOT done)
    message(FATAL_ERROR "np ${np}, ${threads} threads: the log does not end with 10 steps done")
  endif()
  if(NOT (np EQUAL 1 AND threads EQUAL 1))
    execute_process(COMMAND "${H5DIFF}" --exclude-path /timing --exclude-path /rve/cost
                            --exclude-path /rve/partition "${DIR}/np1_t1/results.h5"
                            "${DIR}/np${np}_t${threads}/results.h5"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "${np} rank(s) x ${threads} threads differ from 1 x 1:\n${out}\n${err}")
    endif()
    message(STATUS "${np} rank(s) x ${threads} OpenMP threads: the same results as 1 x 1")
  endif()
endforeach()
