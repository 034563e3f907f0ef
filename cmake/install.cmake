# CMake package: `find_package(stipple CONFIG)` gives stipple::runtime (C and C++ API),
# stipple::anim and stipple::platform (headless contexts). The bake is a tool, not a library:
# the package defines stipple::bake (the installed stipple-bake) and stipple_bake_assets()
# (cmake/stippleBake.cmake) to bake models at an integrator's build time. stipple.pc gives
# the runtime to pkg-config users (docs/build-integration.md).
include(CMakePackageConfigHelpers)
set_target_properties(stipple_anim PROPERTIES EXPORT_NAME anim)
set_target_properties(stipple_runtime PROPERTIES EXPORT_NAME runtime)
set_target_properties(stipple_platform PROPERTIES EXPORT_NAME platform)
install(TARGETS stipple_anim stipple_runtime stipple_platform EXPORT stippleTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS stipple-bake stipple-play RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir anim runtime platform)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stipple/${dir}
          FILES_MATCHING PATTERN "*.h"
          PATTERN "window_context.h" EXCLUDE)  # the kiosk window: a tool's, not installed
endforeach()
install(EXPORT stippleTargets NAMESPACE stipple::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple)
set(STIPPLE_INSTALL_BINDIR ${CMAKE_INSTALL_BINDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/stippleConfig.cmake.in
  ${PROJECT_BINARY_DIR}/stippleConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple
  PATH_VARS STIPPLE_INSTALL_BINDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stippleConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/stippleConfig.cmake ${PROJECT_BINARY_DIR}/stippleConfigVersion.cmake
        ${PROJECT_SOURCE_DIR}/cmake/stippleBake.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple)

# stipple.pc: the C API (and the C++ one) for pkg-config users. Only static archives are
# installed, so Libs names the runtime, then anim (its dependency), then the C++ runtime
# libraries the C compiler does not link by itself (stdc++, m with GCC): a C program links
# with `cc app.c $(pkg-config --cflags --libs stipple)`. The runtime reaches GL only through
# the get-proc-address the caller passes: no GLESv2/EGL libraries. A sanitizer build's
# archives are instrumented, so its stipple.pc adds -fsanitize=... to Libs. The paths are
# relative to the .pc file (${pcfiledir}), so `cmake --install --prefix <any>` works.
set(_stipple_pc_libs)
foreach(_lib IN LISTS CMAKE_CXX_IMPLICIT_LINK_LIBRARIES)
  if(NOT _lib IN_LIST CMAKE_C_IMPLICIT_LINK_LIBRARIES AND NOT _lib IN_LIST _stipple_pc_libs)
    list(APPEND _stipple_pc_libs ${_lib})
  endif()
endforeach()
list(TRANSFORM _stipple_pc_libs REPLACE "^([^-/].*)$" "-l\\1")
if(STIPPLE_SANITIZE)
  list(APPEND _stipple_pc_libs -fsanitize=${STIPPLE_SANITIZE})
endif()
list(JOIN _stipple_pc_libs " " STIPPLE_PC_EXTRA_LIBS)
# Requires.private: glm (header-only): pkg-config adds its Cflags for the C++ API's headers.
set(STIPPLE_PC_REQUIRES_PRIVATE)
pkg_check_modules(_STIPPLE_PC_GLM QUIET glm)
if(_STIPPLE_PC_GLM_FOUND)
  set(STIPPLE_PC_REQUIRES_PRIVATE "Requires.private: glm")
endif()
foreach(_dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${_dir}}")
    set(STIPPLE_PC_${_dir} "${CMAKE_INSTALL_${_dir}}")
  else()
    set(STIPPLE_PC_${_dir} "\${prefix}/${CMAKE_INSTALL_${_dir}}")
  endif()
endforeach()
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(STIPPLE_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _rel "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
  string(REGEX REPLACE "/$" "" _rel "${_rel}")
  set(STIPPLE_PC_PREFIX "\${pcfiledir}/${_rel}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/stipple.pc.in ${PROJECT_BINARY_DIR}/stipple.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/stipple.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
