// The texture atlas layout: each base face's triangle inside its cell, two
// to a cell, the same orientation everywhere, gutters that keep texels of
// different faces apart, and barycentric coordinates mapped linearly.
#include "texture/atlas_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace meshwave {
namespace {

double SignedArea(const std::array<AtlasPoint, 3>& t) {
  return 0.5 * ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y));
}

// Distance from point p to the segment ab.
double ToSegment(AtlasPoint p, AtlasPoint a, AtlasPoint b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

TEST(AtlasLayoutTest, RefusesWhatCannotBeLaidOut) {
  EXPECT_EQ(AtlasLayout::Create(0, 64, 2).status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(AtlasLayout::Create(10, 48, 2).ok());   // not a power of two
  EXPECT_FALSE(AtlasLayout::Create(10, 4, 0).ok());    // too small
  EXPECT_FALSE(AtlasLayout::Create(10, 16, 4).ok());   // the gutter leaves no room
  EXPECT_FALSE(AtlasLayout::Create(1u << 20, 1024, 4).ok());  // wider than 16384
  auto ok = AtlasLayout::Create(10, 16, 2);
  ASSERT_TRUE(ok.ok()) << ok.status().ToString();
}

TEST(AtlasLayoutTest, LaysFacesOutTwoToACellInRows) {
  auto layout = AtlasLayout::Create(99, 32, 2);
  ASSERT_TRUE(layout.ok());
  EXPECT_EQ(layout->columns(), 8u);  // 50 cells: about square
  EXPECT_EQ(layout->rows(), 7u);
  EXPECT_EQ(layout->width(), 256u);
  EXPECT_EQ(layout->height(), 224u);
  auto fixed = AtlasLayout::Create(99, 32, 2, 50);
  ASSERT_TRUE(fixed.ok());
  EXPECT_EQ(fixed->rows(), 1u);
}

TEST(AtlasLayoutTest, TrianglesStayInTheirCellsApartByTheirGutters) {
  for (uint32_t gutter : {0u, 1u, 2u, 4u}) {
    auto layout = AtlasLayout::Create(7, 64, gutter);
    ASSERT_TRUE(layout.ok());
    const double first_area = SignedArea(layout->Triangle(0));
    for (uint32_t f = 0; f < 7; ++f) {
      const auto t = layout->Triangle(f);
      EXPECT_DOUBLE_EQ(SignedArea(t), first_area) << f;  // one orientation, one size
      const uint32_t k = f / 2;
      const double x0 = (k % layout->columns()) * 64.0, y0 = (k / layout->columns()) * 64.0;
      for (const AtlasPoint& p : t) {
        EXPECT_GE(p.x, x0 + gutter);
        EXPECT_LE(p.x, x0 + 64 - gutter);
        EXPECT_GE(p.y, y0 + gutter);
        EXPECT_LE(p.y, y0 + 64 - gutter);
      }
    }
    // The two triangles of a cell: every corner of one at least 2 gutters
    // from every edge of the other.
    const auto a = layout->Triangle(0), b = layout->Triangle(1);
    for (const AtlasPoint& p : b) {
      for (int e = 0; e < 3; ++e) EXPECT_GE(ToSegment(p, a[e], a[(e + 1) % 3]), 2.0 * gutter - 1e-9);
    }
  }
}

TEST(AtlasLayoutTest, MapsBarycentricCoordinatesLinearly) {
  auto layout = AtlasLayout::Create(4, 16, 1);
  ASSERT_TRUE(layout.ok());
  const auto t = layout->Triangle(3);
  const AtlasPoint c0 = layout->Map(3, 1, 0, 0), c2 = layout->Map(3, 0, 0, 1);
  EXPECT_DOUBLE_EQ(c0.x, t[0].x);
  EXPECT_DOUBLE_EQ(c0.y, t[0].y);
  EXPECT_DOUBLE_EQ(c2.x, t[2].x);
  const AtlasPoint mid = layout->Map(3, 0, 0.5, 0.5);
  EXPECT_DOUBLE_EQ(mid.x, 0.5 * (t[1].x + t[2].x));
  EXPECT_DOUBLE_EQ(mid.y, 0.5 * (t[1].y + t[2].y));
}

}  // namespace
}  // namespace meshwave
