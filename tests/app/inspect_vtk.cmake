# `mpmxdem inspect CKPT --rve ID --vtk DIR` end to end (issue 19, grain-scale views): a small
# coupled run on 2 ranks writes a checkpoint; inspect writes the views of two RVEs and of all of
# them; tools/mpmxdem_tools/checks/check_grain_vtk.py (xml.etree + h5py, no ParaView) compares them with the checkpoint
# and fails on a damaged view. Refusals: a missing id, an unusable DIR and a checkpoint without
# DEM RVEs end with exit 2, a message naming the checkpoint, and nothing written.
# Usage: cmake -DEXE -DMPIEXEC -DDIR [-DPYTHON] -P inspect_vtk.cmake (from the source root)
include("${CMAKE_CURRENT_LIST_DIR}/hostile_util.cmake")
file(REMOVE_RECURSE "${DIR}")
file(MAKE_DIRECTORY "${DIR}")

function(run_ok)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  TIMEOUT 120)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

run_ok("${MPIEXEC}" -n 2 --bind-to none "${EXE}" run jobs/triaxial_mpmxdem_small.toml
       --out "${DIR}/run" --max-steps 6)
set(ckpt "${DIR}/run/checkpoint_0000000006.h5")
run_ok("${EXE}" inspect "${ckpt}" --rve 5 --rve 2 --vtk "${DIR}/two")
foreach(f IN ITEMS "RVE 2 " "RVE 5 " "spheres," "contacts;" "Z without rattlers")
  string(FIND "${out}" "${f}" pos)
  if(pos EQUAL -1)
    message(FATAL_ERROR "inspect --rve output lacks '${f}':\n${out}")
  endif()
endforeach()
file(GLOB two RELATIVE "${DIR}/two" "${DIR}/two/*")
list(SORT two)
set(expected rve_2.pvd rve_2_step_6.vtm rve_2_step_6_cell.vtu rve_2_step_6_contacts.vtp
    rve_2_step_6_spheres.vtp rve_5.pvd rve_5_step_6.vtm rve_5_step_6_cell.vtu
    rve_5_step_6_contacts.vtp rve_5_step_6_spheres.vtp)
if(NOT "${two}" STREQUAL "${expected}")
  message(FATAL_ERROR "inspect --vtk wrote:\n${two}\nexpected:\n${expected}")
endif()
# The same view again: the time series keeps one entry for it (check_grain_vtk.py checks).
run_ok("${EXE}" inspect "${ckpt}" --rve 2 --vtk "${DIR}/two")
run_ok("${EXE}" inspect "${ckpt}" --rve all --vtk "${DIR}/all")
file(GLOB all "${DIR}/all/*.vtm")
list(LENGTH all n_all)
if(NOT n_all EQUAL 8)
  message(FATAL_ERROR "inspect --rve all wrote ${n_all} .vtm files, expected 8 (one per RVE)")
endif()

set(have_h5py FALSE)
if(PYTHON)
  execute_process(COMMAND "${PYTHON}" -c "import h5py, numpy" RESULT_VARIABLE rc OUTPUT_QUIET
                  ERROR_QUIET)
  if(rc EQUAL 0)
    set(have_h5py TRUE)
  else()
    message(STATUS "no h5py for ${PYTHON}: tools/mpmxdem-tools check_grain_vtk not run")
  endif()
endif()
if(have_h5py)
  run_ok("${PYTHON}" tools/mpmxdem-tools check_grain_vtk "${ckpt}" "${DIR}/two" --expect 2)
  message(STATUS "${out}")
  run_ok("${PYTHON}" tools/mpmxdem-tools check_grain_vtk "${ckpt}" "${DIR}/all" --expect 8)
  # The check can fail: one radius changed in a copy of a view.
  file(COPY "${DIR}/two/" DESTINATION "${DIR}/damaged")
  file(READ "${DIR}/damaged/rve_2_step_6_spheres.vtp" text)
  string(FIND "${text}" "Name=\"radius\"" at)
  string(SUBSTRING "${text}" ${at} -1 tail)
  string(REGEX MATCH "\n          ([^ \n]+)\n" line "${tail}")
  string(REPLACE "${CMAKE_MATCH_1}" "1e-3" tail_bad "${tail}")
  string(SUBSTRING "${text}" 0 ${at} head)
  file(WRITE "${DIR}/damaged/rve_2_step_6_spheres.vtp" "${head}${tail_bad}")
  execute_process(COMMAND "${PYTHON}" tools/mpmxdem-tools check_grain_vtk "${ckpt}" "${DIR}/damaged"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  expect_failure("${rc}" "${out}" 1 "radius != spheres/r")
endif()

# Refusals: exit 2, the checkpoint named, nothing written.
execute_process(COMMAND "${EXE}" inspect "${ckpt}" --rve 3 --rve 99 --vtk "${DIR}/missing"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "checkpoint ${ckpt}: --rve 99: no RVE with this point id"
               "ids 0..7")
if(EXISTS "${DIR}/missing")
  message(FATAL_ERROR "a refused inspect created ${DIR}/missing")
endif()
file(WRITE "${DIR}/afile" "x\n")
execute_process(COMMAND "${EXE}" inspect "${ckpt}" --rve 1 --vtk "${DIR}/afile/sub"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "checkpoint ${ckpt}: --vtk ${DIR}/afile/sub" "not a directory")
snapshot("${DIR}/two" before)
execute_process(COMMAND "${EXE}" inspect "${ckpt}" --rve 1 --rve 1000000 --vtk "${DIR}/two"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "--rve 1000000")
expect_unchanged("${DIR}/two" "${before}" "a refused inspect")
# A time series that this program did not write is not overwritten.
file(WRITE "${DIR}/foreign/rve_4.pvd" "<something else/>\n")
snapshot("${DIR}/foreign" before)
execute_process(COMMAND "${EXE}" inspect "${ckpt}" --rve 4 --vtk "${DIR}/foreign"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "${DIR}/foreign/rve_4.pvd: not a time series written by")
expect_unchanged("${DIR}/foreign" "${before}" "a refused inspect")
execute_process(COMMAND "${EXE}" inspect "${ckpt}" --vtk "${DIR}/norve"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "--vtk requires --rve")

# A checkpoint of elastic material points has no grains.
run_ok("${MPIEXEC}" -n 2 --bind-to none "${EXE}" run jobs/elastic_triaxial.toml
       --out "${DIR}/elastic" --max-steps 2)
set(eckpt "${DIR}/elastic/checkpoint_0000000002.h5")
execute_process(COMMAND "${EXE}" inspect "${eckpt}" --rve 0 --vtk "${DIR}/elastic_views"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "checkpoint ${eckpt}: --rve 0: this RVE is not a DEM cell")
execute_process(COMMAND "${EXE}" inspect "${eckpt}" --rve all --vtk "${DIR}/elastic_views"
                RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
expect_failure("${rc}" "${err}" 2 "checkpoint ${eckpt}: --rve all: the checkpoint holds no DEM RVE")
if(EXISTS "${DIR}/elastic_views")
  message(FATAL_ERROR "a refused inspect created ${DIR}/elastic_views")
endif()
