# `cmake --install` of a build configured with MESHWAVE_DECODER_ONLY: the
# decoder library, its own public headers (codec/include/decoder) and a
# CMake package whose find_package(meshwave) gives meshwave::decoder alone.
# Nothing of the encoder, the protocol, the server or the client
# (tests/codec/decoder_install_test.sh checks the installed tree).
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

set_target_properties(meshwave_decoder PROPERTIES EXPORT_NAME decoder)
install(TARGETS meshwave_decoder
  EXPORT meshwaveDecoderTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/codec/include/decoder/meshwave
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")

set(MESHWAVE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/meshwave)
install(EXPORT meshwaveDecoderTargets NAMESPACE meshwave:: DESTINATION ${MESHWAVE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/meshwaveDecoderConfig.cmake.in
  ${PROJECT_BINARY_DIR}/meshwaveConfig.cmake INSTALL_DESTINATION ${MESHWAVE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/meshwaveConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/meshwaveConfig.cmake
              ${PROJECT_BINARY_DIR}/meshwaveConfigVersion.cmake
  DESTINATION ${MESHWAVE_CMAKE_DIR})
