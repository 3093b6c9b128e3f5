// The texture atlas of a semi-regular mesh (docs/FORMAT.md, "Texture
// atlas"): every base face owns a triangle of texels, two faces to a square
// cell, so a point of the surface given by its base face and barycentric
// coordinates has fixed texture coordinates. UVs therefore never travel:
// the encoder bakes textures into this layout and the decoder computes
// every vertex's UV from it, at any level.
#ifndef MESHWAVE_TEXTURE_ATLAS_LAYOUT_H_
#define MESHWAVE_TEXTURE_ATLAS_LAYOUT_H_

#include <array>
#include <cstdint>

#include "meshwave/status.h"

namespace meshwave {

// Texel coordinates: x to the right, y down, the atlas's top-left corner at
// (0, 0), texel (i, j) covering [i, i+1) x [j, j+1) (its centre at
// (i + 0.5, j + 0.5)). UV = (x / width, y / height): glTF's convention.
struct AtlasPoint {
  double x = 0, y = 0;
};

class AtlasLayout {
 public:
  // The layout of `base_faces` faces in square cells of `cell` texels with
  // a gutter of `gutter` texels around each triangle; `columns` cells a
  // row (0: the smallest count that makes the atlas about square).
  // kInvalidArgument unless cell is a power of two in [8, 4096], gutter
  // leaves each triangle at least 2 texels across (cell >= 4 * gutter + 8,
  // checked), base_faces >= 1, and the atlas at most 16384 texels a side.
  static Result<AtlasLayout> Create(uint32_t base_faces, uint32_t cell, uint32_t gutter,
                                    uint32_t columns = 0);

  uint32_t base_faces() const { return base_faces_; }
  uint32_t cell() const { return cell_; }
  uint32_t gutter() const { return gutter_; }
  uint32_t columns() const { return columns_; }
  uint32_t rows() const { return rows_; }
  uint32_t width() const { return columns_ * cell_; }
  uint32_t height() const { return rows_ * cell_; }

  // The corners of base face f's triangle (f < base_faces), in the order
  // of the face's corners: the point with barycentric coordinates
  // (b0, b1, b2) maps to b0 P0 + b1 P1 + b2 P2.
  std::array<AtlasPoint, 3> Triangle(uint32_t f) const;
  AtlasPoint Map(uint32_t f, double b0, double b1, double b2) const;

 private:
  uint32_t base_faces_ = 0, cell_ = 0, gutter_ = 0, columns_ = 0, rows_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_ATLAS_LAYOUT_H_
