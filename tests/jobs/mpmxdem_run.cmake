# mpmxdem_run(<np> <args>...): runs `MPIEXEC -n <np> --bind-to none EXE run <args>...` from a CMake
# script (the caller sets EXE and MPIEXEC); a failure stops the script with the run's output.
function(mpmxdem_run np)
  execute_process(COMMAND "${MPIEXEC}" -n ${np} --bind-to none "${EXE}" run ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mpmxdem run ${ARGN} on ${np} ranks failed (${rc}):\n${out}\n${err}")
  endif()
endfunction()

# mpmxdem_check(<script> <args>...): runs `PYTHON <script> <args>...` (the caller sets PYTHON) and
# prints its output; exit 77 (a Python module such as h5py missing) prints "SKIPPED" (the tests'
# SKIP_REGULAR_EXPRESSION), any other non-zero exit stops the script. Call it last in a script.
function(mpmxdem_check script)
  execute_process(COMMAND "${PYTHON}" "${script}" ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(rc EQUAL 77)
    message("SKIPPED: a Python module ${script} needs is missing (h5py)")
  elseif(NOT rc EQUAL 0)
    get_filename_component(name "${script}" NAME)
    message(FATAL_ERROR "${name} failed (${rc})")
  endif()
endfunction()

# mpmxdem_job_with(<job> <table> <lines> <out>): writes <out>, a copy of <job> with <lines>
# (separated by '|') added at the start of its [<table>] table (the job must have that table and
# must not name files relative to its own directory).
function(mpmxdem_job_with job table lines out)
  file(READ "${job}" text)
  string(FIND "${text}" "\n[${table}]\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${job} has no [${table}] table to add '${lines}' to")
  endif()
  string(REPLACE "|" "\n" add "${lines}")
  string(REPLACE "\n[${table}]\n" "\n[${table}]\n${add}\n" text "${text}")
  file(WRITE "${out}" "${text}")
endfunction()
