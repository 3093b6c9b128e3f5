// The base colour of a MeshAsset's surface as the texture bake reads it
// (material factor x base colour texture x vertex colour, in linear light;
// glTF's UV convention, wrap modes and UV transforms): for tools that draw
// an asset as it looks, such as `meshwave render`.
#ifndef MESHWAVE_ASSET_APPEARANCE_H_
#define MESHWAVE_ASSET_APPEARANCE_H_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>

#include "meshwave/mesh.h"
#include "meshwave/mesh_asset.h"

namespace meshwave {

// The linear RGBA base colour at barycentric weights `w` of face `face`
// (alpha 1 for opaque materials); nullopt where a masked material's alpha
// cutoff removes the surface. `asset` must outlive the function, and its
// indices be a reader's (in range).
using BaseColorFunction =
    std::function<std::optional<Eigen::Vector4f>(uint32_t face, const Vec3& w)>;
BaseColorFunction AssetBaseColor(const MeshAsset& asset);

// Linear light to the nearest 8-bit sRGB value (IEC 61966-2-1).
uint8_t LinearToSrgb8(float linear);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_APPEARANCE_H_
