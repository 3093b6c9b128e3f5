#include "texture/atlas_coordinates.h"

#include <cstddef>

namespace meshwave {
namespace {

AtlasPoint Mid(const AtlasPoint& a, const AtlasPoint& b) {
  return {(a.x + b.x) / 2, (a.y + b.y) / 2};
}

struct Writer {
  double inv_width = 0, inv_height = 0;
  float* out = nullptr;

  // Face `face` of `depth` more levels under corners p: its children 4 face
  // + c (meshwave/semiregular.h) one level down, recursively; at depth 0
  // its UVs. Midpoints of texel coordinates on a power-of-two grid are
  // exact, so a vertex shared by faces (or levels) gets the same UV.
  void Descend(uint64_t face, int depth, const std::array<AtlasPoint, 3>& p) {
    if (depth == 0) {
      float* uv = out + 6 * face;
      for (size_t i = 0; i < 3; ++i) {
        uv[2 * i] = static_cast<float>(p[i].x * inv_width);
        uv[2 * i + 1] = static_cast<float>(p[i].y * inv_height);
      }
      return;
    }
    const AtlasPoint ab = Mid(p[0], p[1]), bc = Mid(p[1], p[2]), ca = Mid(p[2], p[0]);
    Descend(4 * face, depth - 1, {p[0], ab, ca});
    Descend(4 * face + 1, depth - 1, {p[1], bc, ab});
    Descend(4 * face + 2, depth - 1, {p[2], ca, bc});
    Descend(4 * face + 3, depth - 1, {ab, bc, ca});
  }
};

}  // namespace

std::array<AtlasPoint, 3> BaseFaceCorners(const AtlasLayout& atlas,
                                          std::span<const uint32_t> face_triangles, uint32_t f) {
  if (face_triangles.empty()) return atlas.Triangle(f);
  const uint32_t t = face_triangles[f] / 3, r = face_triangles[f] % 3;
  const std::array<AtlasPoint, 3> corners = atlas.Triangle(t);
  return {corners[r], corners[(1 + r) % 3], corners[(2 + r) % 3]};
}

std::vector<float> AtlasCoordinates(const AtlasLayout& atlas,
                                    std::span<const uint32_t> face_triangles, int level) {
  const uint64_t per_base = uint64_t{1} << (2 * level);
  std::vector<float> out(6 * per_base * atlas.base_faces());
  Writer writer{1.0 / atlas.width(), 1.0 / atlas.height(), out.data()};
  for (uint32_t f = 0; f < atlas.base_faces(); ++f) {
    writer.Descend(f, level, BaseFaceCorners(atlas, face_triangles, f));
  }
  return out;
}

}  // namespace meshwave
