# Interface targets carrying the project's warning, optimisation and sanitizer flags.
add_library(mpmxdem_options INTERFACE)
target_compile_options(mpmxdem_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wno-psabi
  $<$<BOOL:${MPMXDEM_WERROR}>:-Werror>)
if(MPMXDEM_NATIVE)
  target_compile_options(mpmxdem_options INTERFACE -march=native)
endif()
if(MPMXDEM_SANITIZE)
  target_compile_options(mpmxdem_options INTERFACE -fsanitize=address,undefined
                         -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(mpmxdem_options INTERFACE -fsanitize=address,undefined)
endif()

# mpmxdem_skip_when_sanitized(<target>...): benchmarks, studies and the verification tests are
# left out of the sanitizer build's default target: `tools/dev test` runs its unit and mpi labels
# only (build them by name there where wanted).
function(mpmxdem_skip_when_sanitized)
  if(MPMXDEM_SANITIZE)
    set_target_properties(${ARGN} PROPERTIES EXCLUDE_FROM_ALL TRUE)
  endif()
endfunction()

# mpmxdem_module(<name> SOURCES ... [PUBLIC_LINK ...] [PRIVATE_LINK ...])
# Creates library target mpmxdem_<name> (alias mpmxdem::<name>). Its headers are reachable as
# "<name>/file.hpp" only through a per-module include root in the build tree, so a module that does
# not link another one cannot include its headers either (src/ itself is never an include root).
function(mpmxdem_module name)
  cmake_parse_arguments(M "" "" "SOURCES;PUBLIC_LINK;PRIVATE_LINK" ${ARGN})
  set(root "${PROJECT_BINARY_DIR}/include/${name}")
  file(MAKE_DIRECTORY "${root}")
  file(CREATE_LINK "${PROJECT_SOURCE_DIR}/src/${name}" "${root}/${name}" SYMBOLIC)
  if(M_SOURCES)
    add_library(mpmxdem_${name} STATIC ${M_SOURCES})
    target_include_directories(mpmxdem_${name} PUBLIC "${root}")
    target_link_libraries(mpmxdem_${name} PUBLIC ${M_PUBLIC_LINK} PRIVATE ${M_PRIVATE_LINK}
                          mpmxdem_options)
  else()
    add_library(mpmxdem_${name} INTERFACE)
    target_include_directories(mpmxdem_${name} INTERFACE "${root}")
    target_link_libraries(mpmxdem_${name} INTERFACE ${M_PUBLIC_LINK})
  endif()
  add_library(mpmxdem::${name} ALIAS mpmxdem_${name})
endfunction()
