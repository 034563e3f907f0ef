# CMake package: `find_package(stipple CONFIG)` gives stipple::runtime (C and C++ API),
# stipple::anim and stipple::platform (headless contexts). The bake is a tool, not a library.
include(CMakePackageConfigHelpers)
set_target_properties(stipple_anim PROPERTIES EXPORT_NAME anim)
set_target_properties(stipple_runtime PROPERTIES EXPORT_NAME runtime)
set_target_properties(stipple_platform PROPERTIES EXPORT_NAME platform)
install(TARGETS stipple_anim stipple_runtime stipple_platform EXPORT stippleTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS stipple-bake stipple-play RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(dir anim runtime platform)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/stipple/${dir}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(EXPORT stippleTargets NAMESPACE stipple::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/stippleConfig.cmake.in
  ${PROJECT_BINARY_DIR}/stippleConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/stippleConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/stippleConfig.cmake ${PROJECT_BINARY_DIR}/stippleConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/stipple)
