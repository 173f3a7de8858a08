# A generated reference must be exactly what `mpmxdem schema` prints: docs/reference/jobs.md
# (regenerate: mpmxdem schema > docs/reference/jobs.md) and, with -DOUTPUTS=1,
# docs/reference/results_h5.md (mpmxdem schema --outputs > docs/reference/results_h5.md).
set(args schema)
set(regen "build/mpmxdem schema > docs/reference/jobs.md")
if(OUTPUTS)
  list(APPEND args --outputs)
  set(regen "build/mpmxdem schema --outputs > docs/reference/results_h5.md")
endif()
execute_process(COMMAND "${EXE}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE generated)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpmxdem ${args} failed (${rc})")
endif()
file(READ "${DOC}" current)
if(NOT current STREQUAL generated)
  message(FATAL_ERROR "${DOC} is out of date: run `${regen}`")
endif()
