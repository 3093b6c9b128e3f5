// The per-format asset readers behind ParseMeshAsset (meshwave/mesh_asset.h).
// Each takes the main file's bytes, already read from `files`.
#ifndef MESHWAVE_ASSET_ASSET_READERS_H_
#define MESHWAVE_ASSET_ASSET_READERS_H_

#include <string_view>

#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

struct GltfReadOptions {
  // False: geometry only (ReadMesh of a .glb): no image is read or decoded
  // and MeshAsset::images stays empty (texture slots keep the glTF image
  // indices); materials and UVs are still converted.
  bool load_images = true;
};

// glTF 2.0, .glb or .gltf (told apart by the bytes).
Result<MeshAsset> ParseGltfAsset(std::string_view bytes, FileSet& files,
                                 std::string_view main_name,
                                 const AssetLimits& limits,
                                 const GltfReadOptions& options = {});

// Wavefront OBJ with its MTL files and their texture images.
Result<MeshAsset> ParseObjAsset(std::string_view bytes, FileSet& files,
                                std::string_view main_name,
                                const AssetLimits& limits);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_ASSET_READERS_H_
