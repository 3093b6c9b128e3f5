#include "remesh/fit_projection.h"

#include <gtest/gtest.h>

#include "codec/remesh/fit_cases_testonly.h"
#include "remesh/qem_simplifier.h"

namespace meshwave::remesh {
namespace {

using testing::FitCase;

void ExpectNear(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_LT((actual - expected).norm(), tolerance)
      << "got (" << actual.transpose() << "), expected ("
      << expected.transpose() << ")";
}

TEST(FitProjectionTest, NewVerticesDropOntoAPlaneAlongTheNormal) {
  FitCase fit(testing::FlatGrid(8, -2, -2, 4), testing::HexagonFan(), 1);
  fit.AnchorToClosest(7);
  // Predictions off the plane, tangentially and along +z.
  const Vec3 offset(0.05, -0.03, 0.3);
  fit.PlaceAtMidpoints(0);
  std::vector<Vec3> predicted(fit.positions.begin() + 7, fit.positions.end());
  for (Vec3& p : predicted) p += offset;
  std::copy(predicted.begin(), predicted.end(), fit.positions.begin() + 7);

  PlaceNewVertices(fit.state(), 0);

  // Straight down: the base's normals are all +z.
  for (uint32_t m = 7; m < 19; ++m) {
    const Vec3& q = predicted[m - 7];
    ExpectNear(fit.positions[m], Vec3(q.x(), q.y(), 0), 1e-12);
    EXPECT_NE(fit.anchors[m].face, InputSurface::kNoFace);
    EXPECT_EQ(fit.anchors[m].loop, BoundaryLoops::kNone);
  }
  EXPECT_EQ(fit.stats.normal_hits, 12u);
  EXPECT_EQ(fit.stats.closest_fallbacks, 0u);
  EXPECT_EQ(fit.stats.boundary_vertices, 0u);
}

TEST(FitProjectionTest, NewVerticesMoveOutOntoASphereAlongTheNormal) {
  // Base: the icosahedron on the unit sphere; input: the same sphere three
  // times finer. Edge midpoints lie inside; the vertex normals of the
  // icosahedron are radial, so each goes radially out onto the input.
  FitCase fit(testing::IcoSphere(3), testing::IcoSphere(0), 1);
  fit.AnchorToClosest(12);
  fit.PlaceAtMidpoints(0);
  const std::vector<Vec3> predicted = fit.positions;

  PlaceNewVertices(fit.state(), 0);

  for (uint32_t m = 12; m < 42; ++m) {
    const Vec3& p = fit.positions[m];
    EXPECT_LT(fit.OffSurface(p), 1e-12) << m;
    EXPECT_NEAR(p.normalized().dot(predicted[m].normalized()), 1.0, 1e-12) << m;
    EXPECT_GT(p.norm(), predicted[m].norm() + 0.1) << m;
  }
  EXPECT_EQ(fit.stats.normal_hits, 30u);
  EXPECT_EQ(fit.stats.closest_fallbacks, 0u);
}

TEST(FitProjectionTest, BoundaryVerticesGoToTheArcLengthMidpointOfTheirLoop) {
  // Input: the square [0, 2]^2 (one boundary loop of length 8); base: its
  // four corners, placed by PlaceBaseVertices from the input vertices.
  const TriMesh input = testing::FlatGrid(4, 0, 0, 2);
  SimplifiedMesh base;
  base.mesh.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  base.mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  base.source_vertex = {0, 4, 24, 20};  // the grid's corners
  base.component = {0, 0, 0, 0};
  FitCase fit(input, base.mesh, 1);
  std::vector<uint8_t> pinned(input.positions.size(), 0);
  pinned[24] = 1;
  std::vector<Vec3> base_positions;
  std::vector<SurfaceAnchor> base_anchors;
  PlaceBaseVertices(base, *fit.surface, pinned, base_positions, base_anchors);
  for (uint32_t v = 0; v < 4; ++v) {
    EXPECT_EQ(base_anchors[v].loop, 0u);
    EXPECT_EQ(base_anchors[v].pinned, v == 2);
    fit.positions[v] = base_positions[v];
    fit.anchors[v] = base_anchors[v];
  }
  fit.PlaceAtMidpoints(0);
  // Predictions above the plane and off the boundary.
  for (uint32_t m = 4; m < 9; ++m) fit.positions[m] += Vec3(0.1, 0.1, 0.2);

  PlaceNewVertices(fit.state(), 0);

  const BoundaryLoops& loops = fit.surface->loops();
  const std::pair<uint32_t, uint32_t> sides[] = {
      {0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (const auto& [a, b] : sides) {
    const uint32_t m = fit.Splitting(0, a, b);
    const Vec3 midpoint = (fit.positions[a] + fit.positions[b]) / 2;
    ExpectNear(fit.positions[m], midpoint, 1e-12);
    EXPECT_EQ(fit.anchors[m].loop, 0u);
    EXPECT_DOUBLE_EQ(fit.anchors[m].s,
                     loops.Midway(0, fit.anchors[a].s, fit.anchors[b].s));
  }
  // The diagonal is inside: down along the normal.
  ExpectNear(fit.positions[fit.Splitting(0, 0, 2)], Vec3(1.1, 1.1, 0), 1e-12);
  EXPECT_EQ(fit.stats.boundary_vertices, 4u);
  EXPECT_EQ(fit.stats.normal_hits, 1u);
}

TEST(FitProjectionTest, FallsBackToTheClosestPointWhereTheNormalMisses) {
  // Input: the unit square; base: one triangle reaching past its right
  // side, so the normals of two new vertices miss the input.
  TriMesh base;
  base.positions = {{0.2, 0.2, 0}, {2.6, 0.2, 0}, {0.2, 0.9, 0}};
  base.faces = {{0, 1, 2}};
  FitCase fit(testing::FlatGrid(4, 0, 0, 1), base, 1);
  fit.AnchorToClosest(3);
  fit.PlaceAtMidpoints(0);
  for (uint32_t m = 3; m < 6; ++m) fit.positions[m] += Vec3(0, 0, 0.1);

  PlaceNewVertices(fit.state(), 0);

  ExpectNear(fit.positions[fit.Splitting(0, 0, 1)], Vec3(1, 0.2, 0), 1e-12);
  ExpectNear(fit.positions[fit.Splitting(0, 1, 2)], Vec3(1, 0.55, 0), 1e-12);
  ExpectNear(fit.positions[fit.Splitting(0, 2, 0)], Vec3(0.2, 0.55, 0), 1e-12);
  EXPECT_EQ(fit.stats.normal_hits, 1u);
  EXPECT_EQ(fit.stats.closest_fallbacks, 2u);
}

}  // namespace
}  // namespace meshwave::remesh
