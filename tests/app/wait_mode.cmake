# farm.wait = "auto" looks at where the ranks really run: two ranks started with --bind-to none
# and OMP_PROC_BIND=close both bind their first thread to the node's first core (the OpenMP
# runtime binds it at start-up), so they share it and must sleep while they wait, not spin, on a
# node of any size (what srun without binding does: docs/guide/cluster.md).
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P ... (from the source root)
file(REMOVE_RECURSE "${DIR}")
set(ENV{OMP_PROC_BIND} close)
set(ENV{OMP_PLACES} cores)
set(ENV{OMP_NUM_THREADS} 1)
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run jobs/elastic_triaxial.toml
                        --out "${DIR}/bound" --max-steps 2
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run failed (${rc}):\n${out}${err}")
endif()
string(FIND "${out}${err}" "waits sleep (auto: the node's threads share cores)" at)
if(at EQUAL -1)
  message(FATAL_ERROR "two ranks bound to one core were not told to sleep:\n${out}${err}")
endif()
message(STATUS "wait mode: ok")
