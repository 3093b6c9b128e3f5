// Loads a glTF document (.glb or .gltf, told apart by the bytes) into
// tinygltf's Model: our GLB parsing and the gate (gltf_gate.h) first, then
// tinygltf with file callbacks that can only hand it the buffers the gate
// resolved, and an image callback that keeps the encoded bytes (decoding is
// ours, with limits). tinygltf's exceptions (it calls vector::at and
// nlohmann-json) become ParseErrors.
#ifndef MESHWAVE_ASSET_GLTF_LOADER_H_
#define MESHWAVE_ASSET_GLTF_LOADER_H_

#include <string>
#include <string_view>
#include <vector>

#include "asset/tiny_gltf_config.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

// `bytes`: the main file's contents. Images given by bufferView or data
// URI end up in Image::image as encoded bytes; external image URIs are
// left for the caller (Image::uri). tinygltf's warnings are appended to
// `warnings`.
Result<tinygltf::Model> LoadGltfModel(std::string_view bytes, FileSet& files,
                                      std::string_view main_name,
                                      const AssetLimits& limits,
                                      std::vector<std::string>* warnings);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_LOADER_H_
