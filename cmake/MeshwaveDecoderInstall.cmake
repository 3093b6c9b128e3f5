# `cmake --install` of a build configured with MESHWAVE_DECODER_ONLY: the
# decoder library, its own public headers (codec/include/decoder) and a
# CMake package whose find_package(meshwave) gives meshwave::decoder alone.
# Nothing of the encoder, the protocol, the server or the client
# (tests/codec/decoder_install_test.sh checks the installed tree).
include(${CMAKE_CURRENT_LIST_DIR}/MeshwavePackage.cmake)
include(GNUInstallDirs)

set_target_properties(meshwave_decoder PROPERTIES EXPORT_NAME decoder)
install(TARGETS meshwave_decoder
  EXPORT meshwaveDecoderTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/codec/include/decoder/meshwave
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")

meshwave_install_package(meshwaveDecoderTargets ${PROJECT_SOURCE_DIR}/cmake/meshwaveDecoderConfig.cmake.in)
