// How alike two meshes look: both rendered from the same cameras with the
// same framing (the reference's), their base colour drawn without light, and
// the luma PSNR over the pixels either covers. An image-based measure in the
// spirit of the one MPEG's mesh-coding tests use: what a textured mesh's
// user sees, texture, UV placement and silhouette together.
#ifndef MESHWAVE_TOOLS_RENDERED_PSNR_H_
#define MESHWAVE_TOOLS_RENDERED_PSNR_H_

#include <cstdint>
#include <vector>

#include "meshwave/mesh_asset.h"
#include "rasterizer.h"

namespace meshwave::cli {

struct RenderedPsnrOptions {
  int views = 16;    // cameras around the object (MetricViews)
  int size = 1024;   // pixels a side of each picture
  // Samples a side per pixel, averaged: what a screen shows with
  // antialiasing and filtered textures. One sample a pixel makes the
  // measure hang on sub-pixel shifts of silhouettes and of fine texture.
  int supersample = 2;
  bool lit = false;  // true: Lambert light as `meshwave render` draws
};

// `count` directions around the object: half 25 degrees above the equator,
// half 25 below, their azimuths interleaved, so that every side is seen.
std::vector<View> MetricViews(int count, int size);

// One picture per view and the pixels the mesh covered (any sample).
struct Pictures {
  std::vector<std::vector<uint8_t>> rgb, covered;
};

// The reference's pictures; its framing is stored in `views` for the others.
Pictures RenderReference(const MeshAsset& reference, std::vector<View>& views,
                         const RenderedPsnrOptions& options);

// `asset` drawn with the views RenderReference framed.
Pictures RenderLike(const MeshAsset& asset, const std::vector<View>& views,
                    const RenderedPsnrOptions& options);

struct LumaPsnr {
  double db = 0;            // +inf when the pictures are equal
  uint64_t object_pixels = 0;  // covered in the reference's picture or in the other
};

// BT.709 luma of the 8-bit sRGB values, squared errors summed over every
// view's object pixels, peak 255.
LumaPsnr CompareLuma(const Pictures& reference, const Pictures& other);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_RENDERED_PSNR_H_
