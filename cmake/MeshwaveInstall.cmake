# `cmake --install`: the decoder, codec, asset, protocol and client
# libraries, their public headers, the generated protobuf headers they
# include, and a CMake
# package so that another project can find_package(meshwave) and link
# meshwave::client. A build configured with MESHWAVE_DECODER_ONLY installs
# the decoder alone (cmake/MeshwaveDecoderInstall.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/MeshwavePackage.cmake)
include(GNUInstallDirs)

# Include directories as seen from the build tree and from an install (the
# libraries' own set them: codec/CMakeLists.txt, protocol/CMakeLists.txt).
set_property(TARGET meshwave_proto PROPERTY INTERFACE_INCLUDE_DIRECTORIES
  "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/proto>"
  "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
set_property(TARGET meshwave_client_proto PROPERTY INTERFACE_INCLUDE_DIRECTORIES
  "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/client>"
  "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/client/proto>"
  "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")

set_target_properties(meshwave_decoder PROPERTIES EXPORT_NAME decoder)
set_target_properties(meshwave_codec PROPERTIES EXPORT_NAME codec)
set_target_properties(meshwave_asset PROPERTIES EXPORT_NAME asset)
set_target_properties(meshwave_core PROPERTIES EXPORT_NAME core)
set_target_properties(meshwave_protocol PROPERTIES EXPORT_NAME protocol)
set_target_properties(meshwave_proto PROPERTIES EXPORT_NAME proto)
set_target_properties(meshwave_client PROPERTIES EXPORT_NAME client)
set_target_properties(meshwave_client_proto PROPERTIES EXPORT_NAME client_proto)
# Static libraries name their private dependencies for linking only; the
# warning flags of meshwave_options do not reach consumers.
set_target_properties(meshwave_options PROPERTIES EXPORT_NAME options)

install(TARGETS meshwave_decoder meshwave_core meshwave_codec meshwave_asset meshwave_protocol
                meshwave_proto meshwave_client meshwave_client_proto meshwave_options
  EXPORT meshwaveTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(_mw_include codec/include/decoder codec/include/encoder protocol/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_mw_include}/meshwave
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/client/include/meshwave
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(DIRECTORY ${PROJECT_BINARY_DIR}/proto/ ${PROJECT_BINARY_DIR}/client/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.pb.h"
  PATTERN "CMakeFiles" EXCLUDE)

meshwave_install_package(meshwaveTargets ${PROJECT_SOURCE_DIR}/cmake/meshwaveConfig.cmake.in)
