// RegionWeight (meshwave/region.h): how much a part of the mesh matters to
// a sphere or a view. The regions' text forms: tests/protocol/region_text_test.cpp.
#include "meshwave/region.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>

namespace meshwave {
namespace {

TEST(RegionTest, ASphereWeighsWhatMeetsItOneAndTheRestLessWithDistance) {
  const Region r{SphereRegion{Vec3::Zero(), 1}, std::nullopt};
  EXPECT_EQ(RegionWeight(r, Vec3(0.5, 0, 0), 0.1), 1);
  EXPECT_EQ(RegionWeight(r, Vec3(1.5, 0, 0), 0.6), 1);  // the ball reaches in
  double previous = 1;
  for (double x : {1.6, 2.0, 3.0, 10.0, 100.0}) {
    const double w = RegionWeight(r, Vec3(x, 0, 0), 0.5);
    EXPECT_LT(w, previous) << x;
    EXPECT_GT(w, 0) << x;
    previous = w;
  }
  // Gap of one sphere radius: 1 / (1 + 1).
  EXPECT_DOUBLE_EQ(RegionWeight(r, Vec3(2.5, 0, 0), 0.5), 0.5);
}

TEST(RegionTest, AViewWeighsByProjectedSizeAndNothingOutsideIt) {
  // Looking down -z from z = 10, 90 degrees vertically, a square screen.
  const Region r{ViewRegion{Vec3(0, 0, 10), Vec3(0, 0, -1), 90, 100, 100}, std::nullopt};
  // tan(45) = 1: projected radius over half height = r / d.
  EXPECT_NEAR(RegionWeight(r, Vec3(0, 0, 0), 1), 0.1, 1e-12);
  EXPECT_NEAR(RegionWeight(r, Vec3(0, 0, 5), 1), 0.2, 1e-12);  // nearer: larger
  EXPECT_EQ(RegionWeight(r, Vec3(0, 0, 20), 1), 0);           // behind the camera
  EXPECT_EQ(RegionWeight(r, Vec3(100, 0, 0), 1), 0);          // far to the side
  EXPECT_EQ(RegionWeight(r, Vec3(0, 0, 10.5), 1), 1);         // the eye is inside
  // Beyond the screen's corner cone (half angle atan(sqrt 2) = 54.7 degrees)
  // only by less than its angular radius: still seen.
  const double x = 10 * std::tan(56 * std::numbers::pi / 180);
  EXPECT_EQ(RegionWeight(r, Vec3(x, 0, 0), 0.01), 0);
  EXPECT_GT(RegionWeight(r, Vec3(x, 0, 0), 2), 0);
  EXPECT_EQ(RegionWeight(r, Vec3(0, 0, 0), 1e9), 1);  // capped
}

}  // namespace
}  // namespace meshwave
