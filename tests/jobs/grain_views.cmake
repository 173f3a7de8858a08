# Grain views during a run (issue 19, docs/design/dem.md "Grain-scale views during a run"), through
# the command line: A runs tests/jobs/grain_views_small.toml to step 90 on 2 ranks; B runs it to
# step 70 on 2 ranks (views 0..60 and 70, checkpoints 30, 60, 70), then restarts on 3 ranks from the
# checkpoint of step 60 to step 90. Checked: B's series rve_<id>.pvd equal A's byte for byte (the
# view of step 70, after the checkpoint, is dropped from the series; 80 and 90 added), every file
# the series name exists and equals A's byte for byte (the views are bit-exact across a restart on
# another rank count), and each spheres file holds the RVE's 100 spheres.
# A view that cannot be written fails the run with exit 4 and the file named.
file(REMOVE_RECURSE "${DIR}")
include(${CMAKE_CURRENT_LIST_DIR}/mpmxdem_run.cmake)
set(job tests/jobs/grain_views_small.toml)
mpmxdem_run(2 ${job} --out "${DIR}/a" --max-steps 90)
mpmxdem_run(2 ${job} --out "${DIR}/b" --max-steps 70)
mpmxdem_run(3 ${job} --out "${DIR}/b" --restart "${DIR}/b/checkpoint_0000000060.h5" --max-steps 90)
foreach(id IN ITEMS 0 5)
  file(READ "${DIR}/a/grains/rve_${id}.pvd" series)
  string(REGEX MATCHALL "file=\"[^\"]+\"" entries "${series}")
  set(expected)
  foreach(step IN ITEMS 0 20 40 60 80 90)
    list(APPEND expected "file=\"rve_${id}_step_${step}.vtm\"")
  endforeach()
  if(NOT entries STREQUAL expected)
    message(FATAL_ERROR "rve_${id}.pvd of the straight run lists ${entries}, expected ${expected}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${DIR}/a/grains/rve_${id}.pvd"
                          "${DIR}/b/grains/rve_${id}.pvd" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    file(READ "${DIR}/b/grains/rve_${id}.pvd" b)
    message(FATAL_ERROR "rve_${id}.pvd differs after the restart:\n${b}")
  endif()
  foreach(step IN ITEMS 0 20 40 60 80 90)
    foreach(part IN ITEMS .vtm _spheres.vtp _contacts.vtp _cell.vtu)
      set(name "rve_${id}_step_${step}${part}")
      execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${DIR}/a/grains/${name}"
                              "${DIR}/b/grains/${name}" RESULT_VARIABLE rc)
      if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${name}: the restarted run's view differs from the straight run's")
      endif()
    endforeach()
    file(READ "${DIR}/a/grains/rve_${id}_step_${step}_spheres.vtp" spheres)
    string(FIND "${spheres}" "NumberOfPoints=\"100\"" pos)
    if(pos EQUAL -1)
      message(FATAL_ERROR "rve_${id}_step_${step}_spheres.vtp does not hold 100 spheres")
    endif()
  endforeach()
endforeach()
# A view that cannot be written (a directory where its staging file goes): exit 4 on every rank,
# with the file and the RVE named, and no hang.
file(MAKE_DIRECTORY "${DIR}/c/grains/rve_5_step_20_cell.vtu.tmp")
execute_process(COMMAND "${MPIEXEC}" -n 2 --bind-to none "${EXE}" run ${job} --out "${DIR}/c" --force
                        --max-steps 30
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${err}" "grain views of step 20 (RVE of point id 5): cannot write" pos)
if(NOT rc EQUAL 4 OR pos EQUAL -1)
  message(FATAL_ERROR "an unwritable view did not fail cleanly with exit 4 (rc ${rc}):\n${err}")
endif()
