# Correctness at many ranks (issue 20, item 1), oversubscribed on a 2-core machine:
#  - 64 tiny RVEs of 4 distinct samples (tests/jobs/many_ranks.toml) on 1, 2, 8, 16 and 32 ranks give
#    the same results.h5, bit for bit (METIS with up to 32 parts, rebalancing that moves RVEs);
#  - a checkpoint written by 32 ranks restarts on 3, and one written by 3 restarts on 32, both equal
#    to the straight run;
#  - 8 RVEs on 16 ranks (8 ranks own nothing) equal the 1-rank run;
#  - with farm.rank0_rves = false (rank 0 runs the MPM only) on 8 ranks, the 1-rank run again;
#  - with fewer than 64 RVEs per rank the start-up log says so (8 ranks), on one rank it does not.
# Rank-count-dependent datasets are left out of the comparison: the measured costs, the partition and
# wall times. Usage: cmake -DEXE -DMPIEXEC -DH5DIFF -DDIR -P ... (from the source root)
file(REMOVE_RECURSE "${DIR}")
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
set(job tests/jobs/many_ranks.toml)
function(same a b what)
  execute_process(COMMAND "${H5DIFF}" --exclude-path /timing --exclude-path /rve/cost
                          --exclude-path /rve/partition "${a}" "${b}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: ${b} differs from ${a}:\n${out}\n${err}")
  endif()
  message(STATUS "${what}: same")
endfunction()

# Straight runs; every run writes checkpoints at steps 5 and 10.
foreach(np 1 2 8 16 32)
  mpmxdem_run(${np} ${job} --out "${DIR}/np${np}" --max-steps 10)
  if(NOT np EQUAL 1)
    same("${DIR}/np1/results.h5" "${DIR}/np${np}/results.h5" "64 RVEs on ${np} ranks")
  endif()
endforeach()

# Fewer than 64 RVEs per rank: the start-up log says so, with the count per rank; one rank does not.
file(STRINGS "${DIR}/np8/log.txt" line REGEX "farm: 8 RVEs per rank: .*fewer ranks with more threads")
if(NOT line)
  message(FATAL_ERROR "np8: the log does not say that 8 RVEs per rank balance badly")
endif()
file(STRINGS "${DIR}/np1/log.txt" line REGEX "RVEs per rank")
if(line)
  message(FATAL_ERROR "np1: the log speaks of RVEs per rank on one rank: ${line}")
endif()

# Restarts across rank counts: 32 -> 3 and 3 -> 32.
file(COPY "${DIR}/np32/checkpoint_0000000005.h5" DESTINATION "${DIR}/from32")
mpmxdem_run(3 ${job} --out "${DIR}/from32" --restart "${DIR}/from32/checkpoint_0000000005.h5"
            --max-steps 10)
mpmxdem_run(3 ${job} --out "${DIR}/np3" --max-steps 5)
mpmxdem_run(32 ${job} --out "${DIR}/np3" --restart "${DIR}/np3/checkpoint_0000000005.h5"
            --max-steps 10)
# The restarted runs' results.h5 hold rows 0..5 of their first part (from32: none, as the
# directory only had the checkpoint) and 5..10 of the restart: compare the checkpoints at step 10
# (the root attributes say how many ranks wrote them: left out; step and time are datasets).
foreach(d from32 np3)
  execute_process(COMMAND "${H5DIFF}" --exclude-path /rve/cost --exclude-path /rve/partition
                          --exclude-attribute /
                          "${DIR}/np1/checkpoint_0000000010.h5" "${DIR}/${d}/checkpoint_0000000010.h5"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "restart ${d}: its step-10 checkpoint differs from the 1-rank run's:\n${out}\n${err}")
  endif()
endforeach()
same("${DIR}/np1/results.h5" "${DIR}/np3/results.h5" "3 ranks to step 5, then 32 ranks to 10")

# Rank 0 left to the MPM: the same job with farm.rank0_rves = false on 8 ranks (7 RVE owners).
file(READ ${job} text)
file(WRITE "${DIR}/rank0_free.toml" "${text}\n[farm]\nrank0_rves = false\n")
mpmxdem_run(8 "${DIR}/rank0_free.toml" --out "${DIR}/rank0_free" --max-steps 10)
same("${DIR}/np1/results.h5" "${DIR}/rank0_free/results.h5" "64 RVEs on ranks 1-7 of 8")
file(STRINGS "${DIR}/rank0_free/log.txt" line REGEX "rank 0: the MPM only")
if(NOT line)
  message(FATAL_ERROR "rank0_free: the log does not say that rank 0 runs the MPM only")
endif()
# Its step-5 checkpoint (rank 0 owned nothing) continues on 3 ranks with the job as it was
# (farm.* may change at a restart): the step-10 checkpoint equals the 1-rank run's.
file(COPY "${DIR}/rank0_free/checkpoint_0000000005.h5" DESTINATION "${DIR}/from_rank0_free")
mpmxdem_run(3 ${job} --out "${DIR}/from_rank0_free"
            --restart "${DIR}/from_rank0_free/checkpoint_0000000005.h5" --max-steps 10)
execute_process(COMMAND "${H5DIFF}" --exclude-path /rve/cost --exclude-path /rve/partition
                        --exclude-attribute /
                        "${DIR}/np1/checkpoint_0000000010.h5"
                        "${DIR}/from_rank0_free/checkpoint_0000000010.h5"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "restart of the rank0_free checkpoint differs from the 1-rank run:\n${out}\n${err}")
endif()

# More ranks than RVEs: 8 RVEs on 16 ranks, 8 of which own nothing.
mpmxdem_run(1 jobs/triaxial_mpmxdem_small.toml --out "${DIR}/small1" --max-steps 6)
mpmxdem_run(16 jobs/triaxial_mpmxdem_small.toml --out "${DIR}/small16" --max-steps 6)
same("${DIR}/small1/results.h5" "${DIR}/small16/results.h5" "8 RVEs on 16 ranks")
