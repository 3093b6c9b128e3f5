// YCoCg: the colour channel's space. The inverse is exact, grey has no
// chroma, and the ranges are those the channel's quantisers assume.
#include "attributes/ycocg.h"

#include <gtest/gtest.h>

#include <random>

namespace meshwave {
namespace {

TEST(YCoCgTest, InverseRestoresRgb) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 rgb(unit(rng), unit(rng), unit(rng));
    EXPECT_LT((YCoCgToRgb(RgbToYCoCg(rgb)) - rgb).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(YCoCgTest, GreyHasNoChroma) {
  for (const double v : {0.0, 0.18, 0.5, 1.0}) {
    const Vec3 y = RgbToYCoCg(Vec3::Constant(v));
    EXPECT_DOUBLE_EQ(y[0], v);
    EXPECT_DOUBLE_EQ(y[1], 0.0);
    EXPECT_DOUBLE_EQ(y[2], 0.0);
  }
}

TEST(YCoCgTest, PrimariesSpanTheDocumentedRanges) {
  EXPECT_EQ(RgbToYCoCg({1, 0, 0}), Vec3(0.25, 0.5, -0.25));
  EXPECT_EQ(RgbToYCoCg({0, 1, 0}), Vec3(0.5, 0.0, 0.5));
  EXPECT_EQ(RgbToYCoCg({0, 0, 1}), Vec3(0.25, -0.5, -0.25));
  EXPECT_EQ(YCoCgToRgb({0.25, 0.5, -0.25}), Vec3(1, 0, 0));
}

}  // namespace
}  // namespace meshwave
