# stipple_bake_assets(TARGET <target> SOURCES <model files...> [OPTIONS <stipple-bake options...>]
#                     [OUTPUT_DIR <dir>] [OUTPUT_VAR <var>])
#
# Installed with the CMake package (included by stippleConfig.cmake; docs/build-integration.md).
# Bakes models (glTF/GLB/OBJ/PLY/STL) into .stip assets at build time with stipple::bake (the
# installed stipple-bake): one custom command per source, <OUTPUT_DIR>/<name>.stip (<name>: the
# source's file name without its last extension), depending on the source, on stipple-bake and
# on a --strokes file named in OPTIONS, so Ninja and Make bake in parallel and rebake only the
# assets whose inputs changed. The outputs are collected in a custom target <target>_assets
# (<target>_assets_2, ... on later calls for the same target) that <target> depends on.
#
#   TARGET      an existing, non-imported target of this project (built after its assets)
#   SOURCES     model files; relative paths resolve against CMAKE_CURRENT_SOURCE_DIR
#   OPTIONS     stipple-bake options for every source (e.g. --points 50000); --quiet is added,
#               -o is not allowed (the function names the outputs)
#   OUTPUT_DIR  where the assets go (default ${CMAKE_CURRENT_BINARY_DIR}/stipple_assets;
#               relative paths resolve against CMAKE_CURRENT_BINARY_DIR)
#   OUTPUT_VAR  set in the caller's scope to the list of .stip paths, in SOURCES order
#
# The bake runs in CMAKE_CURRENT_SOURCE_DIR, and a relative --strokes FILE resolves there too.
include_guard(GLOBAL)

function(stipple_bake_assets)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;OUTPUT_DIR;OUTPUT_VAR" "SOURCES;OPTIONS")
  set(fn "stipple_bake_assets")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "${fn}: unexpected arguments: ${arg_UNPARSED_ARGUMENTS} (expected TARGET, "
                        "SOURCES, OPTIONS, OUTPUT_DIR, OUTPUT_VAR)")
  endif()
  if(NOT arg_TARGET)
    message(FATAL_ERROR "${fn}: TARGET <target> is required (the target that uses the assets)")
  endif()
  if(NOT TARGET "${arg_TARGET}")
    message(FATAL_ERROR "${fn}: TARGET '${arg_TARGET}' is not a target; call ${fn} after the "
                        "add_executable/add_library/add_custom_target that creates it")
  endif()
  set(target "${arg_TARGET}")
  get_target_property(aliased "${target}" ALIASED_TARGET)
  if(aliased)
    set(target "${aliased}")
  endif()
  get_target_property(imported "${target}" IMPORTED)
  if(imported)
    message(FATAL_ERROR "${fn}: TARGET '${arg_TARGET}' is an imported target; pass a target this "
                        "project builds")
  endif()
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "${fn}: SOURCES <model files...> is required (TARGET ${arg_TARGET})")
  endif()
  if(NOT TARGET stipple::bake)
    message(FATAL_ERROR "${fn}: stipple::bake is not defined: the stipple package found has no "
                        "stipple-bake (set STIPPLE_BAKE_EXECUTABLE before find_package(stipple) "
                        "to name one)")
  endif()

  # OPTIONS: -o is ours; a --strokes file is an input (absolute, and a dependency).
  set(options)
  set(option_depends)
  set(strokes_next FALSE)
  foreach(opt IN LISTS arg_OPTIONS)
    if(strokes_next)
      get_filename_component(opt "${opt}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
      list(APPEND option_depends "${opt}")
      set(strokes_next FALSE)
    elseif(opt STREQUAL "--strokes")
      set(strokes_next TRUE)
    elseif(opt MATCHES "^--strokes=(.+)$")
      get_filename_component(file "${CMAKE_MATCH_1}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
      list(APPEND option_depends "${file}")
      set(opt "--strokes=${file}")
    elseif(opt MATCHES "^(-o|--output)(=.*)?$")
      message(FATAL_ERROR "${fn}: OPTIONS must not contain ${opt}: the outputs are "
                          "<OUTPUT_DIR>/<name>.stip (TARGET ${arg_TARGET})")
    endif()
    list(APPEND options "${opt}")
  endforeach()
  if(strokes_next)
    message(FATAL_ERROR "${fn}: OPTIONS ends with --strokes and no file (TARGET ${arg_TARGET})")
  endif()

  if(arg_OUTPUT_DIR)
    get_filename_component(out_dir "${arg_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  else()
    set(out_dir "${CMAKE_CURRENT_BINARY_DIR}/stipple_assets")
  endif()

  set(outputs)
  get_property(baked GLOBAL PROPERTY _STIPPLE_BAKED_OUTPUTS)
  foreach(src IN LISTS arg_SOURCES)
    get_filename_component(src "${src}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    get_source_file_property(generated "${src}" GENERATED)
    if(NOT generated AND NOT EXISTS "${src}")
      message(FATAL_ERROR "${fn}: source '${src}' does not exist (TARGET ${arg_TARGET})")
    endif()
    get_filename_component(name "${src}" NAME_WLE)
    set(out "${out_dir}/${name}.stip")
    if(out IN_LIST baked)
      message(FATAL_ERROR "${fn}: '${out}' is already baked by another source or call (two "
                          "sources named '${name}'?); pass another OUTPUT_DIR (TARGET ${arg_TARGET})")
    endif()
    list(APPEND baked "${out}")
    add_custom_command(OUTPUT "${out}"
      COMMAND "${CMAKE_COMMAND}" -E make_directory "${out_dir}"
      COMMAND stipple::bake "${src}" -o "${out}" ${options} --quiet
      DEPENDS "${src}" stipple::bake ${option_depends}
      WORKING_DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}"
      COMMENT "Baking ${name}"
      VERBATIM)
    list(APPEND outputs "${out}")
  endforeach()
  set_property(GLOBAL PROPERTY _STIPPLE_BAKED_OUTPUTS "${baked}")

  set(assets_target "${target}_assets")
  set(n 2)
  while(TARGET "${assets_target}")
    set(assets_target "${target}_assets_${n}")
    math(EXPR n "${n} + 1")
  endwhile()
  add_custom_target("${assets_target}" DEPENDS ${outputs})
  add_dependencies("${target}" "${assets_target}")
  if(arg_OUTPUT_VAR)
    set("${arg_OUTPUT_VAR}" "${outputs}" PARENT_SCOPE)
  endif()
endfunction()
