#include "metrics/point_kdtree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "random_points_testonly.h"

namespace meshwave::metrics {
namespace {

using testing::RandomPoints;

PointKdTree::Nearest BruteForceNearest(const std::vector<Vec3>& points,
                                       const Vec3& q) {
  PointKdTree::Nearest best;
  for (uint32_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - q).squaredNorm();
    if (d2 < best.distance_squared) best = {i, d2};
  }
  return best;
}

TEST(PointKdTreeTest, MatchesBruteForceOnRandomPoints) {
  const std::vector<Vec3> points = RandomPoints(5000, 1.0, 1);
  const PointKdTree tree(points);
  for (const Vec3& q : RandomPoints(3000, 1.0, 2)) {
    const PointKdTree::Nearest expected = BruteForceNearest(points, q);
    const PointKdTree::Nearest found = tree.FindNearest(q);
    ASSERT_EQ(found.index, expected.index);
    ASSERT_EQ(found.distance_squared, expected.distance_squared);
  }
}

TEST(PointKdTreeTest, FindsEveryPointOfItsOwnSet) {
  const std::vector<Vec3> points = RandomPoints(2000, 1.0, 3);
  const PointKdTree tree(points);
  for (uint32_t i = 0; i < points.size(); ++i) {
    const PointKdTree::Nearest found = tree.FindNearest(points[i]);
    ASSERT_EQ(found.index, i);
    ASSERT_EQ(found.distance_squared, 0);
  }
}

TEST(PointKdTreeTest, EquallyNearPointsResolveToTheLowestIndex) {
  // A lattice with every point stored three times, in scrambled order.
  std::vector<Vec3> points;
  for (int copy = 0; copy < 3; ++copy) {
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j) points.emplace_back((i * 7) % 10, j, 0);
    }
  }
  const PointKdTree tree(points);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const Vec3 q(i, j, 0.5);
      const PointKdTree::Nearest expected = BruteForceNearest(points, q);
      const PointKdTree::Nearest found = tree.FindNearest(q);
      EXPECT_EQ(found.index, expected.index);
      EXPECT_LT(found.index, 100u);  // a first copy
    }
  }
}

TEST(PointKdTreeTest, EmptySetReportsNoPoint) {
  const PointKdTree tree({});
  const PointKdTree::Nearest found = tree.FindNearest({0, 0, 0});
  EXPECT_EQ(found.index, PointKdTree::kNoPoint);
  EXPECT_TRUE(std::isinf(found.distance_squared));
}

TEST(PointKdTreeTest, SinglePointIsAlwaysNearest) {
  const PointKdTree tree({Vec3(1, 2, 3)});
  const PointKdTree::Nearest found = tree.FindNearest({4, 6, 3});
  EXPECT_EQ(found.index, 0u);
  EXPECT_DOUBLE_EQ(found.distance_squared, 25);
}

}  // namespace
}  // namespace meshwave::metrics
