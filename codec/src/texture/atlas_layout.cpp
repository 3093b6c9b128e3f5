#include "texture/atlas_layout.h"

#include <cmath>
#include <string>

namespace meshwave {
namespace {

constexpr uint32_t kMaxSide = 16384;

}  // namespace

Result<AtlasLayout> AtlasLayout::Create(uint32_t base_faces, uint32_t cell, uint32_t gutter,
                                        uint32_t columns) {
  if (base_faces == 0) return InvalidArgument("atlas: no base faces");
  if (cell < 8 || cell > 4096 || (cell & (cell - 1)) != 0) {
    return InvalidArgument("atlas: cell of " + std::to_string(cell) +
                           " texels (a power of two from 8 to 4096)");
  }
  if (cell < 4 * uint64_t{gutter} + 8) {
    return InvalidArgument("atlas: a gutter of " + std::to_string(gutter) +
                           " texels leaves no room in cells of " + std::to_string(cell));
  }
  const uint64_t cells = (uint64_t{base_faces} + 1) / 2;
  if (columns == 0) {
    columns = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(cells))));
  }
  const uint64_t rows = (cells + columns - 1) / columns;
  if (uint64_t{columns} * cell > kMaxSide || rows * cell > kMaxSide) {
    return InvalidArgument("atlas: " + std::to_string(columns) + " x " + std::to_string(rows) +
                           " cells of " + std::to_string(cell) + " texels exceed " +
                           std::to_string(kMaxSide) + " texels a side");
  }
  AtlasLayout layout;
  layout.base_faces_ = base_faces;
  layout.cell_ = cell;
  layout.gutter_ = gutter;
  layout.columns_ = columns;
  layout.rows_ = static_cast<uint32_t>(rows);
  return layout;
}

std::array<AtlasPoint, 3> AtlasLayout::Triangle(uint32_t f) const {
  const uint32_t k = f / 2;
  const double x0 = static_cast<double>((k % columns_) * cell_);
  const double y0 = static_cast<double>((k / columns_) * cell_);
  const double s = cell_, g = gutter_;
  // The two triangles of a cell face each other across its diagonal; their
  // long edges are 2 * gutter apart (the shift d along both axes moves a
  // line x + y = c by d * sqrt(2)), so neither's gutter reaches the other.
  const double d = std::ceil(std::sqrt(2.0) * g);
  if (f % 2 == 0) {
    return {AtlasPoint{x0 + g, y0 + g}, AtlasPoint{x0 + s - g - d, y0 + g},
            AtlasPoint{x0 + g, y0 + s - g - d}};
  }
  return {AtlasPoint{x0 + s - g, y0 + s - g}, AtlasPoint{x0 + g + d, y0 + s - g},
          AtlasPoint{x0 + s - g, y0 + g + d}};
}

AtlasPoint AtlasLayout::Map(uint32_t f, double b0, double b1, double b2) const {
  const auto t = Triangle(f);
  return {b0 * t[0].x + b1 * t[1].x + b2 * t[2].x, b0 * t[0].y + b1 * t[1].y + b2 * t[2].y};
}

}  // namespace meshwave
