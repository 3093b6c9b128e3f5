#include "metrics/triangle_bvh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "metrics/closest_point_triangle.h"
#include "random_points_testonly.h"
#include "test_meshes_testonly.h"

namespace meshwave::metrics {
namespace {

using testing::RandomPoints;

double BruteForceDistanceSquared(const TriMesh& mesh, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Face& f : mesh.faces) {
    best = std::min(
        best, ClosestPointOnTriangle(p, mesh.positions[f[0]],
                                     mesh.positions[f[1]], mesh.positions[f[2]])
                  .distance_squared);
  }
  return best;
}

// Checks distance, face and point of every hit against brute force.
void ExpectMatchesBruteForce(const TriMesh& mesh,
                             const std::vector<Vec3>& queries) {
  const TriangleBvh bvh(mesh.positions, mesh.faces);
  uint32_t hint = TriangleBvh::kNoFace;
  for (size_t i = 0; i < queries.size(); ++i) {
    const Vec3& p = queries[i];
    const double expected = BruteForceDistanceSquared(mesh, p);
    const TriangleBvh::Hit hit = bvh.ClosestPoint(p);
    ASSERT_EQ(hit.distance_squared, expected) << "query " << i;
    ASSERT_LT(hit.face, mesh.faces.size());
    const Face& f = mesh.faces[hit.face];
    const PointOnTriangle on_face = ClosestPointOnTriangle(
        p, mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]]);
    ASSERT_EQ(on_face.distance_squared, expected);
    ASSERT_EQ(hit.point, on_face.point);
    // A hint, right or wrong, never changes the distance.
    const TriangleBvh::Hit hinted = bvh.ClosestPoint(p, hint);
    ASSERT_EQ(hinted.distance_squared, expected) << "query " << i;
    hint = hinted.face;
  }
}

TEST(TriangleBvhTest, MatchesBruteForceOnRandomTriangleSoup) {
  TriMesh soup;
  soup.positions = RandomPoints(3 * 500, 1.0, 1);
  for (uint32_t i = 0; i < 500; ++i)
    soup.faces.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  ExpectMatchesBruteForce(soup, RandomPoints(3000, 1.5, 2));
}

TEST(TriangleBvhTest, MatchesBruteForceNearABumpySurface) {
  TriMesh sphere = testing::Icosphere(3);  // 1280 faces
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> bump(0.9, 1.1);
  for (Vec3& p : sphere.positions) p *= bump(rng);
  std::vector<Vec3> queries = RandomPoints(2000, 1.2, 4);
  // Queries right on the surface, where pruning is tightest.
  for (size_t i = 0; i < 1000; ++i) {
    const Face& f = sphere.faces[(i * 7) % sphere.faces.size()];
    queries.push_back((sphere.positions[f[0]] + sphere.positions[f[1]] +
                       sphere.positions[f[2]]) /
                      3.0);
  }
  ExpectMatchesBruteForce(sphere, queries);
}

TEST(TriangleBvhTest, HandlesDegenerateAndDuplicateFaces) {
  TriMesh mesh = testing::GridPatch(8, 0, 0, 1);
  const uint32_t v = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.push_back({0.5, 0.5, 0.3});
  mesh.positions.push_back({0.7, 0.5, 0.3});
  mesh.positions.push_back({0.9, 0.5, 0.3});
  mesh.faces.push_back({v, v + 1, v + 2});  // collinear
  mesh.faces.push_back({v, v, v});          // a single point
  mesh.faces.push_back(mesh.faces[0]);      // duplicate
  ExpectMatchesBruteForce(mesh, RandomPoints(2000, 1.2, 5));
}

TEST(TriangleBvhTest, MatchesBruteForceOnGeometricallySpacedTriangles) {
  // Positions shrinking by 1.5 each time: area-heuristic splits peel off a
  // few faces per level, so the tree must fall back to median splits to
  // keep its depth (and the query stack) bounded.
  TriMesh mesh;
  for (uint32_t k = 0; k < 1500; ++k) {
    const double x = std::pow(1.5, -static_cast<double>(k));
    mesh.positions.push_back({x, 0, 0});
    mesh.positions.push_back({x, 0.5 * x, 0});
    mesh.positions.push_back({x, 0, 0.5 * x});
    mesh.faces.push_back({3 * k, 3 * k + 1, 3 * k + 2});
  }
  const TriangleBvh bvh(mesh.positions, mesh.faces);
  EXPECT_GT(bvh.depth(), 32);  // the fallback was needed
  EXPECT_LE(bvh.depth(), TriangleBvh::kMaxDepth);
  std::vector<Vec3> queries = RandomPoints(500, 1.0, 7);
  for (Vec3& q : RandomPoints(500, 1e-6, 8)) queries.push_back(q);
  ExpectMatchesBruteForce(mesh, queries);
}

TEST(TriangleBvhTest, ManyCoincidentCentroidsStillBuildABalancedTree) {
  // 4096 copies of one triangle: the median split must still terminate.
  TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.faces.assign(4096, Face{0, 1, 2});
  const TriangleBvh bvh(mesh.positions, mesh.faces);
  EXPECT_LT(bvh.node_count(), 2 * 4096u);
  EXPECT_EQ(bvh.depth(), 10);  // 4096 / 2^10 = 4 faces per leaf
  EXPECT_DOUBLE_EQ(bvh.ClosestPoint({0.25, 0.25, 2}).distance_squared, 4);
}

TEST(TriangleBvhTest, EmptyTreeReportsNoFace) {
  const TriangleBvh bvh({}, {});
  const TriangleBvh::Hit hit = bvh.ClosestPoint({1, 2, 3}, 0);
  EXPECT_EQ(hit.face, TriangleBvh::kNoFace);
  EXPECT_TRUE(std::isinf(hit.distance_squared));
}

TEST(TriangleBvhTest, OutOfRangeHintIsIgnored) {
  const TriMesh mesh = testing::GridPatch(4, 0, 0, 1);
  const TriangleBvh bvh(mesh.positions, mesh.faces);
  const TriangleBvh::Hit hit = bvh.ClosestPoint({0.5, 0.5, 1}, 1000000);
  EXPECT_DOUBLE_EQ(hit.distance_squared, 1);
}

TEST(TriangleBvhTest, FloatBoxesStayConservativeFarFromTheOrigin) {
  // Coordinates that float cannot hold exactly: rounding the boxes inward
  // would prune the true nearest face.
  TriMesh mesh = testing::Translated(testing::GridPatch(16, 0, 0, 1e-3),
                                     Vec3(1e5 + 0.1, 1e5 + 0.1, 3.3e4));
  std::vector<Vec3> queries = RandomPoints(1000, 1e-3, 6);
  for (Vec3& q : queries) q += Vec3(1e5 + 0.1005, 1e5 + 0.1005, 3.3e4);
  ExpectMatchesBruteForce(mesh, queries);
}

}  // namespace
}  // namespace meshwave::metrics
