# Driven by ctest: install, configure + build the consumer, bake, run.
file(REMOVE_RECURSE ${WORK_DIR})
function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
step(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
step(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package_consumer -B ${WORK_DIR}/build
     -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
step(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
step(${BIN_DIR}/stipple-bake ${SOURCE_DIR}/assets/CesiumMan/CesiumMan.glb -o ${WORK_DIR}/man.stip
     --points 10000 --quiet)
step(${WORK_DIR}/build/consumer ${WORK_DIR}/man.stip)
message(STATUS "consumer drew ${last_output} dark pixels")
