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

// Where the picture is centred and how many pixels a unit of length takes.
// Comparisons of two meshes take one framing for both, so that their
// pixels correspond (each mesh's own box would shift a decoded mesh).
struct Framing {
  Vec3 centre = Vec3::Zero();  // in eye space (after the view's rotation)
  double pixels_per_unit = 1;
};

struct View {
  double azimuth_deg = 0;    // rotation about the vertical (y) axis
  double elevation_deg = 0;  // then about the horizontal (x) axis
  int width = 800, height = 800;
  std::optional<Framing> framing;  // none: the mesh fitted with a margin
};

using Rgb8 = std::array<uint8_t, 3>;

// The colour of a pixel of face `face`: `weights` are the pixel centre's
// barycentric weights on the face's corners (in the face's corner order;
// the view is orthographic, so they are the surface's own), `light` the
// Lambert light at those corners (0.25 ambient to 1). nullopt leaves the
// pixel to whatever lies behind (a masked-out texel).
using PixelShader =
    std::function<std::optional<Rgb8>(uint32_t face, const Vec3& weights, const Vec3& light)>;

// The framing that fits `mesh` to the view's image with a margin.
Framing FitFraming(const TriMesh& mesh, const View& view);

// Renders `mesh` over a white background (framed by view.framing, or
// fitted), each covered pixel coloured by `shade`. Both sides of a face are
// lit (meshes with holes show their inside). Returns width*height*3 bytes,
// rows top to bottom; `covered`, when given, gets width*height bytes, 1
// where the mesh was drawn.
std::vector<uint8_t> Rasterize(const TriMesh& mesh, const PixelShader& shade, const View& view,
                               std::vector<uint8_t>* covered = nullptr);

// Rasterize with one linear RGB colour (0..1) per vertex, lit per vertex,
// interpolated, then encoded with a 1/2.2 gamma (the geometry renders:
// grey, or error colours).
std::vector<uint8_t> Rasterize(const TriMesh& mesh, const std::vector<Vec3>& colours,
                               const View& view);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_RASTERIZER_H_
