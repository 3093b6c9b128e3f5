# meshwave_asset (meshwave::asset, included from codec/CMakeLists.txt;
# headers in include/encoder/meshwave: reading input is the encoder's side):
# mesh assets with their attributes, materials and images
# (meshwave/mesh_asset.h, meshwave/file_set.h): the glTF 2.0 reader
# (tinygltf), the OBJ + MTL reader, texture decoding (libpng, libjpeg-turbo,
# libwebp) and file sets.
# Standard C++ and Debian's libraries; meshwave_codec links it and adds the
# entry points that also need the geometry readers: ReadMesh and ParseMesh,
# which read glTF geometry through it (src/asset/mesh_read.cpp), and
# ParseMeshAsset's PLY colours and OFF (src/asset/mesh_asset_io.cpp).
find_package(PNG REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(TurboJpeg REQUIRED IMPORTED_TARGET GLOBAL libturbojpeg)
pkg_check_modules(WebP REQUIRED IMPORTED_TARGET GLOBAL libwebp)
find_package(nlohmann_json 3.9 REQUIRED GLOBAL)
# tinygltf: the header only. Its implementation is compiled into
# meshwave_asset (src/asset/tiny_gltf_impl.cpp, with the switches of
# src/asset/tiny_gltf_config.h), not linked from Debian's libtinygltf.so.
pkg_check_modules(TinyGltf REQUIRED tinygltf>=2.7)
find_path(MESHWAVE_TINY_GLTF_INCLUDE_DIR tiny_gltf.h HINTS ${TinyGltf_INCLUDE_DIRS} REQUIRED)

add_library(meshwave_asset STATIC
  src/asset/file_set.cpp
  src/asset/weld.cpp
  src/asset/asset_image.cpp
  src/asset/asset_summary.cpp
  src/asset/glb_container.cpp
  src/asset/gltf_gate.cpp
  src/asset/gltf_loader.cpp
  src/asset/gltf_accessor.cpp
  src/asset/gltf_scene.cpp
  src/asset/gltf_materials.cpp
  src/asset/gltf_notes.cpp
  src/asset/gltf_reader.cpp
  src/asset/tiny_gltf_impl.cpp
  src/asset/mtl_reader.cpp
  src/asset/obj_asset_reader.cpp
  src/image/image_decoder.cpp
  src/image/png_decoder.cpp
  src/image/jpeg_decoder.cpp
  src/image/webp_decoder.cpp
  src/image/image_encoder.cpp
)
# tinygltf's implementation must see TINYGLTF_IMPLEMENTATION before any
# other inclusion of its header: never in a unity batch.
set_source_files_properties(src/asset/tiny_gltf_impl.cpp PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
target_include_directories(meshwave_asset
  PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include/encoder>
         $<INSTALL_INTERFACE:include>
  PRIVATE src)
target_include_directories(meshwave_asset SYSTEM PRIVATE ${MESHWAVE_TINY_GLTF_INCLUDE_DIR})
target_link_libraries(meshwave_asset
  PUBLIC meshwave_decoder Eigen3::Eigen
  PRIVATE PNG::PNG PkgConfig::TurboJpeg PkgConfig::WebP $<BUILD_INTERFACE:meshwave_options>
    # Header-only: needed to build, not by what links the installed library.
    $<BUILD_INTERFACE:nlohmann_json::nlohmann_json>)

target_sources(meshwave_codec PRIVATE src/asset/mesh_read.cpp src/asset/mesh_asset_io.cpp)
target_link_libraries(meshwave_codec PUBLIC meshwave_asset)
