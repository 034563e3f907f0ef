# BakeBytes.* (tests/CMakeLists.txt): a bake's bytes are the recorded ones.
#   cmake -DEXPECTED=<sha256> -DFILE=<baked.stip> -P check_bake_bytes.cmake        (fixture's bake)
#   cmake -DEXPECTED=<sha256> -DBAKE=<stipple-bake> -DINPUT=<file> -DOPTIONS="<options>"
#         -DFILE=<scratch.stip> -P check_bake_bytes.cmake                          (bakes first)
if(BAKE)
  separate_arguments(options UNIX_COMMAND "${OPTIONS}")
  execute_process(COMMAND "${BAKE}" "${INPUT}" -o "${FILE}" ${options} --quiet
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "stipple-bake ${INPUT} ${OPTIONS} failed (${rc}):\n${out}")
  endif()
endif()
if(NOT EXISTS "${FILE}")
  message(FATAL_ERROR "no baked asset at ${FILE}")
endif()
file(SHA256 "${FILE}" actual)
if(BAKE)
  file(REMOVE "${FILE}")
endif()
if(NOT actual STREQUAL EXPECTED)
  message(FATAL_ERROR "bake bytes changed: ${INPUT} ${OPTIONS}\n  recorded ${EXPECTED}\n  now      ${actual}\n"
                      "If the change is intended, update tests/bake/bake_checksums.txt.")
endif()
message(STATUS "bytes as recorded: ${EXPECTED}")
