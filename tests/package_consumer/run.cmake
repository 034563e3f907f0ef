# Driven by ctest: install, configure + build the consumer (which bakes its models with
# stipple_bake_assets), check the bake is incremental, run the consumer, then check stipple.pc.
file(REMOVE_RECURSE ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
set(prefix ${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
# A sanitizer build installs instrumented libraries: the consumer links the runtime too.
set(sanitize_flags)
if(SANITIZE)
  set(sanitize_flags -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE})
endif()
# The models the consumer bakes: a scratch copy, so touching one leaves the source tree alone.
file(COPY ${SOURCE_DIR}/assets/RiggedSimple ${SOURCE_DIR}/assets/SimpleSkin
     DESTINATION ${WORK_DIR}/models)
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package_consumer -B ${WORK_DIR}/build
     -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
     -DCONSUMER_MODEL_DIR=${WORK_DIR}/models ${sanitize_flags})

# build(<expected bakes...>): builds the consumer; exactly the named assets are baked.
function(build)
  step(${CMAKE_COMMAND} --build ${WORK_DIR}/build --parallel 2)
  string(REGEX MATCHALL "Baking [A-Za-z0-9_.-]+" baked "${last_output}")
  list(TRANSFORM baked REPLACE "^Baking " "")
  list(SORT baked)
  set(expected ${ARGN})
  list(SORT expected)
  if(NOT "${baked}" STREQUAL "${expected}")
    message(FATAL_ERROR "expected the build to bake [${expected}], it baked [${baked}]:\n"
                        "${last_output}")
  endif()
endfunction()
build(RiggedSimple SimpleSkin)
build()  # nothing changed: nothing baked
file(TOUCH ${WORK_DIR}/models/RiggedSimple/RiggedSimple.glb)
build(RiggedSimple)  # only the changed model
file(TOUCH ${prefix}/bin/stipple-bake)
build(RiggedSimple SimpleSkin)  # a new stipple-bake rebakes everything
message(STATUS "stipple_bake_assets baked only what changed")

# The consumer's baked assets (OUTPUT_VAR, written at configure time) and ASSET, baked by the
# fixture step (tests/test_assets.txt).
file(READ ${WORK_DIR}/build/baked_assets.txt baked_assets)
step(${WORK_DIR}/build/consumer ${baked_assets} ${ASSET})
message(STATUS "consumer drew (dark pixels):\n${last_output}")

# stipple.pc: a C program compiles and links against the install with pkg-config's flags.
find_program(pkg_config pkg-config)
if(NOT C_COMPILER)
  find_program(C_COMPILER cc)
endif()
if(NOT pkg_config OR NOT C_COMPILER)
  message(STATUS "skipped the stipple.pc check: no pkg-config or no C compiler")
  return()
endif()
get_filename_component(libdir ${LIBDIR} ABSOLUTE BASE_DIR ${prefix})
set(ENV{PKG_CONFIG_PATH} ${libdir}/pkgconfig)
step(${pkg_config} --cflags --libs stipple)
string(STRIP "${last_output}" pc_flags)
message(STATUS "pkg-config --cflags --libs stipple: ${pc_flags}")
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
step(${C_COMPILER} -Wall -Wextra -Werror ${SOURCE_DIR}/tests/package_consumer/pc_check.c ${pc_flags}
     -o ${WORK_DIR}/pc_check)
step(${WORK_DIR}/pc_check)
message(STATUS "pc_check (built with pkg-config's flags): ${last_output}")
