# Restart continues only what the checkpoint is a state of (issue 13, class 3), on 2 ranks:
#  - a changed physical key is refused, naming the key and its two values;
#  - a checkpoint of another job is refused;
#  - a directory holding another run's results is refused;
#  - a changed end time is accepted.
# Every refusal exits 2 and leaves the output directory byte-identical.
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P ... (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/elastic_triaxial.toml a_text)
file(WRITE "${DIR}/a.toml" "${a_text}")
string(REPLACE "points_per_cell = 2" "points_per_cell = 1" b_text "${a_text}")
file(WRITE "${DIR}/b.toml" "${b_text}")
string(REPLACE "young_modulus = \"50 MPa\"" "young_modulus = \"60 MPa\"" e_text "${a_text}")
file(WRITE "${DIR}/a_young.toml" "${e_text}")
string(REPLACE "end_time = \"2 s\"" "end_time = \"3 s\"" t_text "${a_text}")
string(APPEND t_text "\n[output]\nevery = 5\n")
file(WRITE "${DIR}/a_longer.toml" "${t_text}")

function(mpmxdem)
  execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" ${ARGN}
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
  set(rc "${rc}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
mpmxdem(run "${DIR}/a.toml" --out "${DIR}/a" --max-steps 10)
expect_failure("${rc}" "${err}" 0)
mpmxdem(run "${DIR}/b.toml" --out "${DIR}/b" --max-steps 10)
expect_failure("${rc}" "${err}" 0)
set(ckpt_a "${DIR}/a/checkpoint_0000000010.h5")
set(ckpt_b "${DIR}/b/checkpoint_0000000010.h5")
snapshot("${DIR}/a" a_before)

mpmxdem(run "${DIR}/a_young.toml" --out "${DIR}/a" --restart "${ckpt_a}" --max-steps 20)
expect_failure("${rc}" "${err}" 2 "cannot restart from ${ckpt_a}"
               "mpm.elastic.young_modulus = 50000000.0 -> 60000000.0")
expect_unchanged("${DIR}/a" "${a_before}" "a restart with a changed young_modulus")

mpmxdem(run "${DIR}/a.toml" --out "${DIR}/a" --restart "${ckpt_b}" --max-steps 20)
expect_failure("${rc}" "${err}" 2 "cannot restart from ${ckpt_b}" "mpm.body[0].points_per_cell = 1 -> 2")
expect_unchanged("${DIR}/a" "${a_before}" "a restart from another job's checkpoint")

file(COPY "${ckpt_b}" DESTINATION "${DIR}/elsewhere")
mpmxdem(run "${DIR}/b.toml" --out "${DIR}/a" --restart "${DIR}/elsewhere/checkpoint_0000000010.h5" --max-steps 20)
expect_failure("${rc}" "${err}" 2 "output directory '${DIR}/a' holds the results of another run"
               "mpm.body[0].points_per_cell = 1 -> 2")
expect_unchanged("${DIR}/a" "${a_before}" "a restart into another run's directory")

mpmxdem(run "${DIR}/a_longer.toml" --out "${DIR}/a" --restart "${ckpt_a}" --max-steps 20)
expect_failure("${rc}" "${err}" 0)
if(NOT EXISTS "${DIR}/a/checkpoint_0000000020.h5")
  message(FATAL_ERROR "the accepted restart wrote no checkpoint at step 20:\n${err}")
endif()
