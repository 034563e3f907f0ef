# ctest fixture step (tests/CMakeLists.txt): bakes one test asset.
#   cmake -DBAKE=<stipple-bake> -DINPUT=<file> -DOUTPUT=<file.stip> -DOPTIONS="<options>" -P bake_asset.cmake
# Writes to a temporary name and renames on success, so a failed bake leaves no asset behind.
separate_arguments(options UNIX_COMMAND "${OPTIONS}")
get_filename_component(dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${dir}")
file(REMOVE "${OUTPUT}")
string(REGEX REPLACE "\\.stip$" ".part.stip" partial "${OUTPUT}")
execute_process(COMMAND "${BAKE}" "${INPUT}" -o "${partial}" ${options} --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  file(REMOVE "${partial}")
  message(FATAL_ERROR "stipple-bake ${INPUT} ${OPTIONS} failed (${rc}):\n${out}")
endif()
file(RENAME "${partial}" "${OUTPUT}")
