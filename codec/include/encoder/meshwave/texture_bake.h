// Baking an asset's textures onto the base-domain atlas of its remesh
// (meshwave/texture.h): every texel of a base face's triangle is a point of
// the remesh's finest surface; its nearest point on the original surface
// gives the original's material there (textures sampled at the original's
// UVs, times factors and vertex colours), so the maps follow the remesh
// and its atlas instead of the original's UV charts.
#ifndef MESHWAVE_TEXTURE_BAKE_H_
#define MESHWAVE_TEXTURE_BAKE_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "meshwave/mesh_asset.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/texture.h"

namespace meshwave {

inline constexpr int kDefaultTextureQuality = 30;

struct TextureBakeOptions {
  // Texels a side of an atlas cell (two base faces a cell): a power of two
  // from 16 to 4096. 0: chosen so that the atlas's triangles hold about as
  // many texels as the original's base-colour images spend on its surface,
  // within `max_side`.
  uint32_t cell = 0;
  uint32_t max_side = 4096;  // atlas texels a side at most (auto cell only)
  // Pyramid levels (full size included). 0: halve until the coarsest level
  // is at most 64 texels a side or its cell would drop below 16 texels.
  int levels = 0;
  // Gutter texels around each triangle at full size. -1: 2^(levels - 1),
  // so the coarsest level keeps one.
  int gutter = -1;
  // Lossy quality (1..100) of the colour maps (WebP) and the
  // metallic-roughness map (JPEG). Low by default: seen on screen a map's
  // resolution counts far more than its quality (docs/RD_RESULTS.md,
  // "Texture code").
  int quality = kDefaultTextureQuality;
  // Worker threads (0: the machine's cores); the result does not depend on
  // it.
  int threads = 0;
};

// What the bake could not carry, one line each for the user: material
// extensions the reader did not carry, alpha cut-offs applied, several
// materials merged into one set of maps.
struct TextureBakeNotes {
  std::vector<std::string> lines;
};

// The asset's material channels baked into an atlas over `remesh`'s base
// faces: base colour (always; WebP, with alpha when any texel is not
// opaque), metallic-roughness with occlusion in R when any material has
// occlusion (glTF's ORM packing; 4:4:4 JPEG), emissive (WebP) and normal
// (tangent space of the atlas, PNG) when some material has them;
// each a pyramid of `levels` images, coarsest first. Material scalars no
// map holds go into BakedTexture::material.
//
// nullopt when no material the faces use has a texture in a carried slot
// and all of them are alike (vertex colours, if any, then travel as a
// colour channel). `remesh` must be a remesh of the asset's surface (its
// points are projected onto it). kInvalidArgument for options out of range,
// an asset whose attributes do not fit its faces, or an atlas that cannot
// hold the base faces.
Result<std::optional<BakedTexture>> BakeTexture(const MeshAsset& asset,
                                                const SemiRegularMesh& remesh,
                                                const TextureBakeOptions& options = {},
                                                TextureBakeNotes* notes = nullptr);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_BAKE_H_
