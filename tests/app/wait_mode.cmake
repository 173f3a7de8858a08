# farm.wait = "auto" looks at where the ranks really run: two ranks started with --bind-to none
# and OMP_PROC_BIND=close both bind their first thread to the node's first core (the OpenMP
# runtime binds it at start-up), so they share it and must sleep while they wait, not spin, on a
# node of any size (what srun without binding does: docs/guide/cluster.md).
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P ... (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
set(ENV{OMP_PROC_BIND} close)
set(ENV{OMP_PLACES} cores)
set(ENV{OMP_NUM_THREADS} 1)
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run jobs/elastic_triaxial.toml
                        --out "${DIR}/bound" --max-steps 2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
expect_failure("${rc}" "${out}${err}" 0 "waits sleep (auto: the node's threads share cores)")
message(STATUS "wait mode: ok")
