# The CMake package both installs write (the whole project's and the
# decoder-only one): the exported targets, meshwaveConfig.cmake from
# CONFIG_IN and its version file, in lib/cmake/meshwave.
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

function(meshwave_install_package export_set config_in)
  set(dir ${CMAKE_INSTALL_LIBDIR}/cmake/meshwave)
  install(EXPORT ${export_set} NAMESPACE meshwave:: DESTINATION ${dir})
  configure_package_config_file(${config_in}
    ${PROJECT_BINARY_DIR}/meshwaveConfig.cmake INSTALL_DESTINATION ${dir})
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/meshwaveConfigVersion.cmake
    COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/meshwaveConfig.cmake
                ${PROJECT_BINARY_DIR}/meshwaveConfigVersion.cmake
    DESTINATION ${dir})
endfunction()
