# Driven by ctest: stipple_bake_assets() (cmake/stippleBake.cmake) refuses bad arguments with a
# clear message, resolves relative SOURCES and --strokes files against the calling directory,
# and rebakes when the --strokes file changes. Runs projects with no compiler and a stand-in
# stipple-bake (a shell script that writes its arguments to the output), so it needs no build.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/fake-bake "#!/bin/sh\nsrc=$1; out=$3; shift 3\nprintf '%s\\n' \"$src\" \"$@\" > \"$out\"\n")
file(CHMOD ${WORK_DIR}/fake-bake PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE)

# project_case(<name> <expected error, or empty> <call...>): configures a project calling
# stipple_bake_assets(<call>) after an add_custom_target(app), then the CMake code in `after`;
# models/ has m.obj, a/m.obj, b/m.obj and s.json.
function(project_case name expected)
  set(dir ${WORK_DIR}/${name})
  foreach(f m.obj a/m.obj b/m.obj s.json)
    file(WRITE ${dir}/models/${f} "${f}\n")
  endforeach()
  list(JOIN ARGN " " call)
  file(WRITE ${dir}/CMakeLists.txt "cmake_minimum_required(VERSION 3.20)
project(${name} NONE)
add_executable(stipple::bake IMPORTED)
set_target_properties(stipple::bake PROPERTIES IMPORTED_LOCATION ${WORK_DIR}/fake-bake)
include(${SOURCE_DIR}/cmake/stippleBake.cmake)
add_custom_target(app ALL)
stipple_bake_assets(${call})
${after}
")
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${dir} -B ${dir}/build
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(expected)
    string(FIND "${err}" "${expected}" at)
    if(rc EQUAL 0 OR at EQUAL -1)
      message(FATAL_ERROR "${name}: expected the configure to fail with '${expected}'; "
                          "rc ${rc}:\n${out}\n${err}")
    endif()
  elseif(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: configure failed:\n${out}\n${err}")
  endif()
endfunction()

project_case(no_target "TARGET <target> is required" SOURCES models/m.obj)
project_case(unknown_target "TARGET 'game' is not a target" TARGET game SOURCES models/m.obj)
project_case(no_sources "SOURCES <model files...> is required" TARGET app)
project_case(missing_source "does not exist" TARGET app SOURCES models/none.obj)
project_case(output_option "must not contain -o" TARGET app SOURCES models/m.obj OPTIONS -o x)
project_case(same_name "already baked" TARGET app SOURCES models/a/m.obj models/b/m.obj)
project_case(unknown_keyword "unexpected arguments" POINTS 5 TARGET app SOURCES models/m.obj)

# Relative SOURCES and --strokes resolve against the calling directory; the strokes file is an
# input: touching it rebakes.
set(dir ${WORK_DIR}/relative)
set(after "file(WRITE \${CMAKE_BINARY_DIR}/baked.txt \${baked})")
project_case(relative "" TARGET app SOURCES models/m.obj OPTIONS --points 7 --strokes models/s.json
             OUTPUT_DIR out OUTPUT_VAR baked)
file(READ ${dir}/build/baked.txt baked)
if(NOT baked STREQUAL "${dir}/build/out/m.stip")
  message(FATAL_ERROR "OUTPUT_VAR: expected ${dir}/build/out/m.stip, got '${baked}'")
endif()
function(build expect_bake)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${dir}/build RESULT_VARIABLE rc
                  OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${out}" "Baking m" at)
  if(NOT rc EQUAL 0 OR (expect_bake AND at EQUAL -1) OR (NOT expect_bake AND NOT at EQUAL -1))
    message(FATAL_ERROR "build (expected a bake: ${expect_bake}) rc ${rc}:\n${out}\n${err}")
  endif()
endfunction()
build(TRUE)
file(READ ${baked} args)
set(expected "${dir}/models/m.obj\n--points\n7\n--strokes\n${dir}/models/s.json\n--quiet\n")
if(NOT args STREQUAL expected)
  message(FATAL_ERROR "stipple-bake ran with\n${args}expected\n${expected}")
endif()
build(FALSE)
file(TOUCH ${dir}/models/s.json)
build(TRUE)
