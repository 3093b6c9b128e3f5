#include "metrics/closest_point_triangle.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <random>

namespace meshwave::metrics {
namespace {

// An independent reference: project on the plane and solve for the
// barycentric coordinates; outside the triangle the answer is on an edge.
PointOnTriangle ReferenceClosestPoint(const Vec3& p, const Vec3& a,
                                      const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  Eigen::Matrix2d gram;
  gram << ab.dot(ab), ab.dot(ac), ab.dot(ac), ac.dot(ac);
  const Eigen::Vector2d uv =
      gram.ldlt().solve(Eigen::Vector2d(ab.dot(p - a), ac.dot(p - a)));
  if (uv[0] >= 0 && uv[1] >= 0 && uv[0] + uv[1] <= 1) {
    const Vec3 q = a + uv[0] * ab + uv[1] * ac;
    return {q, (p - q).squaredNorm()};
  }
  PointOnTriangle best = ClosestPointOnSegment(p, a, b);
  for (const auto& other :
       {ClosestPointOnSegment(p, b, c), ClosestPointOnSegment(p, c, a)}) {
    if (other.distance_squared < best.distance_squared) best = other;
  }
  return best;
}

class BvhClosestPointTest : public ::testing::Test {
 protected:
  const Vec3 a_{0, 0, 0};
  const Vec3 b_{2, 0, 0};
  const Vec3 c_{0, 2, 0};

  void ExpectClosest(const Vec3& p, const Vec3& expected) {
    const PointOnTriangle q = ClosestPointOnTriangle(p, a_, b_, c_);
    EXPECT_NEAR((q.point - expected).norm(), 0, 1e-15) << p.transpose();
    EXPECT_NEAR(q.distance_squared, (p - expected).squaredNorm(), 1e-14);
  }
};

TEST_F(BvhClosestPointTest, PointsBeyondCornersMapToTheCorners) {
  ExpectClosest({-1, -1, 3}, a_);
  ExpectClosest({3, -0.5, -1}, b_);
  ExpectClosest({-0.5, 3, 2}, c_);
}

TEST_F(BvhClosestPointTest, PointsBeyondEdgesProjectOnTheEdges) {
  ExpectClosest({1, -1, 1}, {1, 0, 0});       // edge ab
  ExpectClosest({-2, 0.5, -1}, {0, 0.5, 0});  // edge ca
  ExpectClosest({2, 2, 0.5}, {1, 1, 0});      // edge bc
  ExpectClosest({1.5, 1.5, 0}, {1, 1, 0});    // in the plane, beyond bc
}

TEST_F(BvhClosestPointTest, PointsAboveTheFaceProjectOnThePlane) {
  ExpectClosest({0.5, 0.5, 3}, {0.5, 0.5, 0});
  ExpectClosest({0.2, 1.1, -0.25}, {0.2, 1.1, 0});
  ExpectClosest({0.5, 0.5, 0}, {0.5, 0.5, 0});  // on the face itself
}

TEST(BvhClosestPointDegenerateTest, CollinearTriangleActsAsItsLongEdge) {
  // c lies between a and b: the triangle is the segment [a, b].
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(1, 0, 0);
  const PointOnTriangle q = ClosestPointOnTriangle({3, 2, 0}, a, b, c);
  EXPECT_NEAR((q.point - Vec3(3, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR(q.distance_squared, 4, 1e-14);
  const PointOnTriangle beyond = ClosestPointOnTriangle({6, 0, 1}, a, b, c);
  EXPECT_NEAR((beyond.point - b).norm(), 0, 1e-15);
}

TEST(BvhClosestPointDegenerateTest, CoincidentCornersGiveFiniteResults) {
  const Vec3 a(1, 1, 1), c(3, 1, 1);
  const PointOnTriangle segment = ClosestPointOnTriangle({2, 0, 1}, a, a, c);
  EXPECT_NEAR((segment.point - Vec3(2, 1, 1)).norm(), 0, 1e-15);
  const PointOnTriangle point = ClosestPointOnTriangle({1, 1, 4}, a, a, a);
  EXPECT_EQ(point.point, a);
  EXPECT_DOUBLE_EQ(point.distance_squared, 9);
}

TEST(BvhClosestPointRandomTest, MatchesReferenceOnRandomTriangles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-1, 1);
  const auto random_point = [&] {
    return Vec3(coord(rng), coord(rng), coord(rng));
  };
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a = random_point(), b = random_point(), c = random_point();
    const Vec3 p = 2 * random_point();
    const PointOnTriangle q = ClosestPointOnTriangle(p, a, b, c);
    const PointOnTriangle ref = ReferenceClosestPoint(p, a, b, c);
    ASSERT_NEAR(q.distance_squared, ref.distance_squared, 1e-12) << i;
    ASSERT_NEAR((q.point - ref.point).norm(), 0, 1e-9) << i;
  }
}

TEST(BvhClosestPointSegmentTest, ClampsToTheEnds) {
  const Vec3 a(0, 0, 0), b(1, 0, 0);
  EXPECT_EQ(ClosestPointOnSegment({-1, 1, 0}, a, b).point, a);
  EXPECT_EQ(ClosestPointOnSegment({2, 1, 0}, a, b).point, b);
  EXPECT_EQ(ClosestPointOnSegment({0.25, 1, 0}, a, b).point, Vec3(0.25, 0, 0));
  EXPECT_EQ(ClosestPointOnSegment({5, 5, 5}, a, a).point, a);
}

}  // namespace
}  // namespace meshwave::metrics
