// The filtered queries of TriangleBvh (closest point over accepted faces,
// nearest crossing of a line), checked against brute force.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

#include "metrics/closest_point_triangle.h"
#include "metrics/triangle_bvh.h"

namespace meshwave::metrics {
namespace {

TriMesh RandomSoup(size_t faces, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coord(-1, 1);
  TriMesh soup;
  for (size_t f = 0; f < faces; ++f) {
    const Vec3 c(coord(rng), coord(rng), coord(rng));
    for (int k = 0; k < 3; ++k) {
      soup.positions.push_back(c +
                               0.2 * Vec3(coord(rng), coord(rng), coord(rng)));
    }
    const auto i = static_cast<uint32_t>(3 * f);
    soup.faces.push_back({i, i + 1, i + 2});
  }
  return soup;
}

// Smallest |t| of a crossing of the line with an accepted face, by brute
// force (Möller-Trumbore without slack).
double BruteLine(const TriMesh& m, const Vec3& o, const Vec3& d, double max_t,
                 const TriangleBvh::FaceFilter& accept) {
  double best = std::numeric_limits<double>::infinity();
  for (uint32_t f = 0; f < m.faces.size(); ++f) {
    if (!accept(f)) continue;
    const Vec3& a = m.positions[m.faces[f][0]];
    const Vec3 e1 = m.positions[m.faces[f][1]] - a;
    const Vec3 e2 = m.positions[m.faces[f][2]] - a;
    const Vec3 p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14) continue;
    const Vec3 s = o - a;
    const double u = s.dot(p) / det;
    const Vec3 q = s.cross(e1);
    const double v = d.dot(q) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double t = e2.dot(q) / det;
    if (std::abs(t) <= max_t) best = std::min(best, std::abs(t));
  }
  return best;
}

TEST(TriangleBvhFilteredTest, NearestLineHitMatchesBruteForce) {
  const TriMesh soup = RandomSoup(400, 3);
  const TriangleBvh bvh(soup.positions, soup.faces);
  const TriangleBvh::FaceFilter even = [](uint32_t f) { return f % 2 == 0; };
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> coord(-1.2, 1.2);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 o(coord(rng), coord(rng), coord(rng));
    const Vec3 d = Vec3(coord(rng), coord(rng), coord(rng)).normalized();
    const double max_t = i % 3 == 0 ? 0.3 : 5.0;
    const auto hit = bvh.NearestLineHit(o, d, max_t, even);
    const double expected = BruteLine(soup, o, d, max_t, even);
    if (std::isinf(expected)) {
      // Only a grazing crossing within the slack may be found.
      if (hit.face != TriangleBvh::kNoFace) {
        EXPECT_LE(std::abs(hit.t), max_t);
      }
      continue;
    }
    ++hits;
    ASSERT_NE(hit.face, TriangleBvh::kNoFace) << i;
    EXPECT_NEAR(std::abs(hit.t), expected, 1e-9) << i;
    EXPECT_EQ(hit.face % 2, 0u);
    EXPECT_TRUE(hit.point.isApprox(o + hit.t * d, 1e-12));
  }
  EXPECT_GT(hits, 100);
}

TEST(TriangleBvhFilteredTest, NearestLineHitLooksBothWays) {
  TriMesh two;
  two.positions = {{-1, -1, 1},    {1, -1, 1},    {0, 1, 1},
                   {-1, -1, -0.5}, {1, -1, -0.5}, {0, 1, -0.5}};
  two.faces = {{0, 1, 2}, {3, 4, 5}};
  const TriangleBvh bvh(two.positions, two.faces);
  const auto all = [](uint32_t) { return true; };
  const auto hit = bvh.NearestLineHit(Vec3::Zero(), Vec3(0, 0, 1), 2, all);
  EXPECT_EQ(hit.face, 1u);  // below, at t = -0.5, nearer than t = 1
  EXPECT_DOUBLE_EQ(hit.t, -0.5);
  const auto upper = bvh.NearestLineHit(Vec3::Zero(), Vec3(0, 0, 1), 2,
                                        [](uint32_t f) { return f == 0; });
  EXPECT_EQ(upper.face, 0u);
  EXPECT_DOUBLE_EQ(upper.t, 1.0);
  const auto out_of_reach =
      bvh.NearestLineHit(Vec3::Zero(), Vec3(0, 0, 1), 0.4, all);
  EXPECT_EQ(out_of_reach.face, TriangleBvh::kNoFace);
}

TEST(TriangleBvhFilteredTest, NearestLineHitDoesNotSlipThroughASharedEdge) {
  // Two triangles sharing the edge x = 0; the line runs exactly through it.
  TriMesh quad;
  quad.positions = {{-1, -1, 0}, {0, -1, 0}, {0, 1, 0}, {1, 1, 0}};
  quad.faces = {{0, 1, 2}, {1, 3, 2}};
  const TriangleBvh bvh(quad.positions, quad.faces);
  const auto hit = bvh.NearestLineHit(Vec3(0, 0.3, 1), Vec3(0, 0, -1), 2,
                                      [](uint32_t) { return true; });
  EXPECT_NE(hit.face, TriangleBvh::kNoFace);
  EXPECT_NEAR(hit.t, 1.0, 1e-12);
}

TEST(TriangleBvhFilteredTest, ClosestPointIfMatchesBruteForce) {
  const TriMesh soup = RandomSoup(300, 5);
  const TriangleBvh bvh(soup.positions, soup.faces);
  const TriangleBvh::FaceFilter third = [](uint32_t f) { return f % 3 == 1; };
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> coord(-1.5, 1.5);
  uint32_t hint = TriangleBvh::kNoFace;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    double expected = std::numeric_limits<double>::infinity();
    for (uint32_t f = 0; f < soup.faces.size(); ++f) {
      if (!third(f)) continue;
      const Face& t = soup.faces[f];
      expected =
          std::min(expected, ClosestPointOnTriangle(p, soup.positions[t[0]],
                                                    soup.positions[t[1]],
                                                    soup.positions[t[2]])
                                 .distance_squared);
    }
    // A wrong hint (rejected by the filter, or far away) changes nothing.
    const auto hit = bvh.ClosestPointIf(p, hint, third);
    ASSERT_EQ(hit.distance_squared, expected) << i;
    EXPECT_EQ(hit.face % 3, 1u);
    hint = static_cast<uint32_t>(i);
    // A bound below the answer finds nothing; above it, the same face.
    const auto bounded = bvh.ClosestPointIf(p, hint, third, 0.99 * expected);
    EXPECT_EQ(bounded.face, TriangleBvh::kNoFace);
    EXPECT_TRUE(std::isinf(bounded.distance_squared));
    EXPECT_EQ(
        bvh.ClosestPointIf(p, hint, third, 1.01 * expected).distance_squared,
        expected);
  }
}

TEST(TriangleBvhFilteredTest, EmptyOrFullyFilteredTreesFindNothing) {
  const TriangleBvh empty({}, {});
  const auto all = [](uint32_t) { return true; };
  EXPECT_EQ(empty.ClosestPointIf(Vec3::Zero(), 0, all).face,
            TriangleBvh::kNoFace);
  EXPECT_EQ(empty.NearestLineHit(Vec3::Zero(), Vec3(1, 0, 0), 1, all).face,
            TriangleBvh::kNoFace);
  const TriMesh soup = RandomSoup(20, 7);
  const TriangleBvh bvh(soup.positions, soup.faces);
  const auto none = [](uint32_t) { return false; };
  EXPECT_EQ(bvh.ClosestPointIf(Vec3::Zero(), 3, none).face,
            TriangleBvh::kNoFace);
  EXPECT_EQ(bvh.NearestLineHit(Vec3::Zero(), Vec3(1, 0, 0), 10, none).face,
            TriangleBvh::kNoFace);
}

}  // namespace
}  // namespace meshwave::metrics
