// The geometry of a glTF scene as one mesh: the node tree walked from the
// default scene (scene 0 without one; every root node without scenes),
// cycles and nodes with two parents refused, each drawn mesh's triangle
// primitives read (strips and fans converted, non-indexed ones numbered),
// positions moved by the node's world matrix, the winding flipped where
// that matrix mirrors.
#ifndef MESHWAVE_ASSET_GLTF_SCENE_H_
#define MESHWAVE_ASSET_GLTF_SCENE_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "asset/tiny_gltf_config.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

struct GltfGeometry {
  TriMesh mesh;                            // not welded
  CornerAttribute<Eigen::Vector2f> uv;     // TEXCOORD_0
  CornerAttribute<Eigen::Vector4f> color;  // COLOR_0, linear RGBA
  std::vector<int32_t> face_material;      // glTF material, -1: none
  std::vector<std::string> notes;          // what the primitives dropped
};

Result<GltfGeometry> BuildGltfGeometry(const tinygltf::Model& model,
                                       std::string_view name,
                                       const AssetLimits& limits);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_SCENE_H_
