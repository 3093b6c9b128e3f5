#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "meshwave/metrics.h"
#include "test_meshes_testonly.h"

namespace meshwave {
namespace {

std::vector<Vec3> SpherePoints() { return testing::Icosphere(3).positions; }

TEST(VertexErrorTest, UniformOffsetGivesThatOffsetAsRmsMaxAndMean) {
  const std::vector<Vec3> reference = SpherePoints();
  std::vector<Vec3> test = reference;
  const double d = 0.003;
  const Vec3 offset = Vec3(1, 2, 2).normalized() * d;  // |offset| = d
  for (Vec3& p : test) p += offset;
  const double peak = 2 * std::sqrt(3.0);
  const Result<VertexErrorStats> stats = VertexError(reference, test, peak);
  ASSERT_TRUE(stats.ok()) << stats.status().ToString();
  EXPECT_NEAR(stats->rms, d, 1e-15);
  EXPECT_NEAR(stats->max, d, 1e-15);
  EXPECT_NEAR(stats->mean, d, 1e-15);
  EXPECT_NEAR(stats->psnr_db, 20 * std::log10(peak / d), 1e-9);
  EXPECT_EQ(stats->peak, peak);
  EXPECT_EQ(stats->count, reference.size());
  EXPECT_FALSE(stats->matched_by_nearest);
  EXPECT_EQ(stats->distinct_matches, reference.size());
}

TEST(VertexErrorTest, RmsWeighsLargeErrorsMoreThanMean) {
  const std::vector<Vec3> reference = {{0, 0, 0}, {1, 0, 0}};
  const std::vector<Vec3> test = {{0, 0, 0}, {1, 0, 2}};  // errors 0 and 2
  const Result<VertexErrorStats> stats = VertexError(reference, test, 1);
  ASSERT_TRUE(stats.ok());
  EXPECT_DOUBLE_EQ(stats->rms, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(stats->mean, 1);
  EXPECT_DOUBLE_EQ(stats->max, 2);
}

TEST(VertexErrorTest, IdenticalVerticesGiveInfinitePsnr) {
  const std::vector<Vec3> v = SpherePoints();
  const Result<VertexErrorStats> stats = VertexError(v, v, 1);
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->rms, 0);
  EXPECT_EQ(stats->psnr_db, std::numeric_limits<double>::infinity());
}

TEST(VertexErrorTest, RejectsDifferentCounts) {
  const std::vector<Vec3> v = SpherePoints();
  const std::vector<Vec3> fewer(v.begin(), v.end() - 1);
  const Result<VertexErrorStats> stats = VertexError(v, fewer, 1);
  ASSERT_FALSE(stats.ok());
  EXPECT_EQ(stats.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(stats.status().message().find(std::to_string(v.size())),
            std::string::npos);
}

TEST(VertexErrorTest, RejectsEmptySets) {
  EXPECT_FALSE(VertexError({}, {}, 1).ok());
  EXPECT_FALSE(VertexErrorByNearest({}, SpherePoints(), 1).ok());
  EXPECT_FALSE(VertexErrorByNearest(SpherePoints(), {}, 1).ok());
}

TEST(VertexErrorTest, RejectsNonFiniteCoordinatesAndBadPeaks) {
  std::vector<Vec3> v = SpherePoints();
  std::vector<Vec3> bad = v;
  bad[5].y() = std::numeric_limits<double>::quiet_NaN();
  const Result<VertexErrorStats> nan = VertexError(v, bad, 1);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("vertex 5"), std::string::npos);
  EXPECT_FALSE(VertexErrorByNearest(bad, v, 1).ok());
  EXPECT_FALSE(VertexError(v, v, 0).ok());
  EXPECT_FALSE(VertexError(v, v, -1).ok());
  EXPECT_FALSE(VertexError(v, v, std::numeric_limits<double>::infinity()).ok());
}

TEST(VertexErrorByNearestTest, RecoversAPermutation) {
  const std::vector<Vec3> reference = SpherePoints();
  std::vector<uint32_t> order(reference.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), std::mt19937_64(11));
  std::vector<Vec3> shuffled;
  for (const uint32_t i : order) shuffled.push_back(reference[i]);

  const Result<VertexErrorStats> by_index = VertexError(reference, shuffled, 2);
  ASSERT_TRUE(by_index.ok());
  EXPECT_GT(by_index->rms, 0.5);  // comparing unrelated points

  const Result<VertexErrorStats> stats =
      VertexErrorByNearest(reference, shuffled, 2);
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->rms, 0);
  EXPECT_EQ(stats->max, 0);
  EXPECT_TRUE(stats->matched_by_nearest);
  EXPECT_EQ(stats->count, reference.size());
  EXPECT_EQ(stats->distinct_matches, reference.size());  // a bijection
}

TEST(VertexErrorByNearestTest, PermutedAndOffsetVerticesGiveTheOffset) {
  // Offsets far below the vertex spacing keep the nearest match right.
  const std::vector<Vec3> reference = SpherePoints();
  std::vector<Vec3> test(reference.rbegin(), reference.rend());
  const double d = 1e-4;
  for (Vec3& p : test) p += Vec3(0, 0, d);
  const Result<VertexErrorStats> stats =
      VertexErrorByNearest(reference, test, 1);
  ASSERT_TRUE(stats.ok());
  EXPECT_NEAR(stats->rms, d, 1e-15);
  EXPECT_NEAR(stats->psnr_db, 20 * std::log10(1 / d), 1e-9);
}

TEST(VertexErrorByNearestTest, CountsTestVerticesMatchedMoreThanOnce) {
  const std::vector<Vec3> reference = {{0, 0, 0}, {0.1, 0, 0}, {5, 0, 0}};
  const std::vector<Vec3> test = {{0.05, 0, 0}, {5, 0, 0}, {9, 9, 9}};
  const Result<VertexErrorStats> stats =
      VertexErrorByNearest(reference, test, 1);
  ASSERT_TRUE(stats.ok());
  EXPECT_EQ(stats->distinct_matches, 2u);
  EXPECT_NEAR(stats->max, 0.05, 1e-15);
}

TEST(VertexErrorTest, PsnrIsTwentyLogTenOfPeakOverRms) {
  EXPECT_DOUBLE_EQ(PsnrDb(1, 0.1), 20);
  EXPECT_DOUBLE_EQ(PsnrDb(10, 0.01), 60);
  EXPECT_EQ(PsnrDb(1, 0), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace meshwave
