// A small software rasterizer for `meshwave render`: orthographic view,
// z-buffer, Lambert light per vertex interpolated over each face (Gouraud),
// each pixel's colour given by a shader: per-vertex colours, or what an
// asset looks like (appearance_shader.h).
#ifndef MESHWAVE_TOOLS_RASTERIZER_H_
#define MESHWAVE_TOOLS_RASTERIZER_H_

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::cli {

struct View {
  double azimuth_deg = 0;    // rotation about the vertical (y) axis
  double elevation_deg = 0;  // then about the horizontal (x) axis
  int width = 800, height = 800;
};

using Rgb8 = std::array<uint8_t, 3>;

// The colour of a pixel of face `face`: `weights` are the pixel centre's
// barycentric weights on the face's corners (in the face's corner order;
// the view is orthographic, so they are the surface's own), `light` the
// Lambert light at those corners (0.25 ambient to 1). nullopt leaves the
// pixel to whatever lies behind (a masked-out texel).
using PixelShader =
    std::function<std::optional<Rgb8>(uint32_t face, const Vec3& weights, const Vec3& light)>;

// Renders `mesh` over a white background, the mesh fitted to the image with
// a margin, each covered pixel coloured by `shade`. Both sides of a face are
// lit (meshes with holes show their inside). Returns width*height*3 bytes,
// rows top to bottom.
std::vector<uint8_t> Rasterize(const TriMesh& mesh, const PixelShader& shade, const View& view);

// Rasterize with one linear RGB colour (0..1) per vertex, lit per vertex,
// interpolated, then encoded with a 1/2.2 gamma (the geometry renders:
// grey, or error colours).
std::vector<uint8_t> Rasterize(const TriMesh& mesh, const std::vector<Vec3>& colours,
                               const View& view);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_RASTERIZER_H_
