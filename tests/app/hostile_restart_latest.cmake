# `run --restart latest` (one command line for every link of a chain of batch jobs), on 2 ranks:
#  - no directory yet: starts from the beginning;
#  - then continues from the newest checkpoint, and a finished run continues with no step;
#  - a damaged newest checkpoint is skipped (named in a warning) for the one before it;
#  - only damaged checkpoints: exit 2 naming them, nothing written;
#  - results but no checkpoint: the usual refusal of a non-empty directory, nothing written.
# Usage: cmake -DEXE -DMPIEXEC -DDIR -P ... (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")
file(READ jobs/elastic_triaxial.toml a_text)
string(REPLACE "end_time = \"2 s\"" "end_time = \"0.1 s\"" a_text "${a_text}")
file(WRITE "${DIR}/a.toml" "${a_text}")

function(mpmxdem)
  execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  set(rc "${rc}" PARENT_SCOPE)
  set(err "${out}${err}" PARENT_SCOPE)
endfunction()
function(expect_file path what)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "${what}: ${path} was not written:\n${err}")
  endif()
endfunction()
function(expect_text text what)
  string(FIND "${err}" "${text}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${what}: the output does not say '${text}':\n${err}")
  endif()
endfunction()

set(run "${DIR}/a")
mpmxdem(run "${DIR}/a.toml" --out "${run}" --restart latest --max-steps 10)
expect_failure("${rc}" "${err}" 0)
expect_text("no checkpoint in ${run} yet: starting from the beginning" "first link")
expect_file("${run}/checkpoint_0000000010.h5" "first link")

mpmxdem(run "${DIR}/a.toml" --out "${run}" --restart latest --max-steps 20)
expect_failure("${rc}" "${err}" 0)
expect_text("continuing from ${run}/checkpoint_0000000010.h5" "second link")
expect_file("${run}/checkpoint_0000000020.h5" "second link")

# The newest checkpoint cut short (a job killed while writing it): the one before is used.
file(READ "${run}/checkpoint_0000000020.h5" head LIMIT 4096 HEX)
file(WRITE "${run}/checkpoint_0000000020.h5" "${head}")
mpmxdem(run "${DIR}/a.toml" --out "${run}" --restart latest --max-steps 30)
expect_failure("${rc}" "${err}" 0)
expect_text("newer checkpoint(s) skipped" "damaged newest checkpoint")
expect_text("${run}/checkpoint_0000000020.h5" "damaged newest checkpoint")
expect_text("continuing from ${run}/checkpoint_0000000010.h5" "damaged newest checkpoint")
expect_file("${run}/checkpoint_0000000030.h5" "third link")

# To the end, then once more: nothing left to do, exit 0.
mpmxdem(run "${DIR}/a.toml" --out "${run}" --restart latest)
expect_failure("${rc}" "${err}" 0)
mpmxdem(run "${DIR}/a.toml" --out "${run}" --restart latest)
expect_failure("${rc}" "${err}" 0)
expect_text("continuing from ${run}/checkpoint_" "a finished run")

# Only damaged checkpoints: refused, nothing written.
set(bad "${DIR}/bad")
file(MAKE_DIRECTORY "${bad}")
file(WRITE "${bad}/checkpoint_0000000005.h5" "not an HDF5 file")
snapshot("${bad}" bad_before)
mpmxdem(run "${DIR}/a.toml" --out "${bad}" --restart latest --max-steps 10)
expect_failure("${rc}" "${err}" 2 "--restart latest: none of the 1 checkpoint file(s)"
               "${bad}/checkpoint_0000000005.h5")
expect_unchanged("${bad}" "${bad_before}" "--restart latest with only damaged checkpoints")

# Results of a run killed before its first checkpoint: not silently overwritten.
set(early "${DIR}/early")
mpmxdem(run "${DIR}/a.toml" --out "${early}" --max-steps 5)
expect_failure("${rc}" "${err}" 0)
file(GLOB ckpts "${early}/checkpoint_*.h5")
file(REMOVE ${ckpts})
snapshot("${early}" early_before)
mpmxdem(run "${DIR}/a.toml" --out "${early}" --restart latest --max-steps 10)
expect_failure("${rc}" "${err}" 2 "${early}")
expect_unchanged("${early}" "${early_before}" "--restart latest over results with no checkpoint")
