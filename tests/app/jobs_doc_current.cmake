# docs/reference/jobs.md must be exactly what `mpmxdem schema` prints (regenerate: mpmxdem schema > docs/reference/jobs.md).
execute_process(COMMAND "${EXE}" schema RESULT_VARIABLE rc OUTPUT_VARIABLE generated)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mpmxdem schema failed (${rc})")
endif()
file(READ "${DOC}" current)
if(NOT current STREQUAL generated)
  message(FATAL_ERROR "docs/reference/jobs.md is out of date: run `build/mpmxdem schema > docs/reference/jobs.md`")
endif()
