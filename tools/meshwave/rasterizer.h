// A small software rasterizer for `meshwave render`: orthographic view,
// z-buffer, Gouraud-interpolated vertex colours with Lambert shading.
#ifndef MESHWAVE_TOOLS_RASTERIZER_H_
#define MESHWAVE_TOOLS_RASTERIZER_H_

#include <array>
#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::cli {

struct View {
  double azimuth_deg = 0;    // rotation about the vertical (y) axis
  double elevation_deg = 0;  // then about the horizontal (x) axis
  int width = 800, height = 800;
};

// Renders `mesh` with one linear RGB colour (0..1) per vertex over a white
// background, the mesh fitted to the image with a margin. Both sides of a
// face are lit (meshes with holes show their inside). Returns width*height*3
// bytes, rows top to bottom.
std::vector<uint8_t> Rasterize(const TriMesh& mesh, const std::vector<Vec3>& colours,
                               const View& view);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_RASTERIZER_H_
