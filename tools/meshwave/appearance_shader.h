// What an asset looks like, for `meshwave render`: a pixel shader that
// draws each face's glTF base colour (material factor x base colour
// texture x vertex colour) under the rasterizer's Lambert light.
#ifndef MESHWAVE_TOOLS_APPEARANCE_SHADER_H_
#define MESHWAVE_TOOLS_APPEARANCE_SHADER_H_

#include "meshwave/mesh_asset.h"
#include "rasterizer.h"

namespace meshwave::cli {

// Whether `asset` looks like more than its geometry: vertex colours, or a
// material with a base colour texture or a factor other than opaque white.
// Assets without render grey, as plain meshes do.
bool HasAppearance(const MeshAsset& asset);

// A shader for Rasterize(asset.mesh, ...). The texture is sampled
// bilinearly at the interpolated UV with its slot's transform and wrap
// modes; `asset` must outlive the shader. Masked materials leave their
// cut-out texels see-through; blended ones are drawn opaque. `lit` false
// draws the base colour as it is (no light): what an image metric of the
// surface's colours compares.
PixelShader AppearanceShader(const MeshAsset& asset, bool lit = true);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_APPEARANCE_SHADER_H_
