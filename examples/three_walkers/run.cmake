# Driven by ctest (tests/examples/CMakeLists.txt): install the build into a scratch prefix,
# configure and build examples/three_walkers against it (stipple_bake_assets bakes its walker),
# and render its frame to OUT.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DOUT=frame.ppm [-DWINDOW_OUT=w.ppm]
#         [-DSANITIZE=...] -P run.cmake
file(REMOVE_RECURSE ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
set(sanitize_flags)
if(SANITIZE)  # a sanitizer build installs instrumented libraries
  set(sanitize_flags -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE})
endif()
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/three_walkers -B ${WORK_DIR}/build
     -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release ${sanitize_flags})
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${WORK_DIR}/build/three_walkers ${OUT} 0.5)
# With a window too, under Xvfb when it is installed (scripts/setup.sh installs it).
find_program(XVFB_RUN xvfb-run)
if(XVFB_RUN AND WINDOW_OUT)
  step(${XVFB_RUN} -a -s "-screen 0 800x600x24" ${WORK_DIR}/build/three_walkers ${WINDOW_OUT}
       0.5 --window 10)
endif()
