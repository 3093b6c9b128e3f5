#include "remesh/fit_relaxation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "codec/remesh/fit_cases_testonly.h"

namespace meshwave::remesh {
namespace {

using testing::FitCase;
using testing::FlatHexagon;

Vec3 RingCentroid(const FitCase& fit, const VertexRings& rings, uint32_t v) {
  Vec3 c = Vec3::Zero();
  for (uint32_t u : rings.Ring(v)) c += fit.positions[u];
  return c / static_cast<double>(rings.Ring(v).size());
}

// FlatHexagon (fit_cases_testonly.h) is a fixed point of relaxation: each
// ring's centroid is the vertex itself.

TEST(FitRelaxationTest, LeavesAnEvenLevelWhereItIs) {
  FitCase fit = FlatHexagon();
  const std::vector<Vec3> before = fit.positions;
  Relax(fit.state(), 1, fit.Rings(1));
  for (uint32_t v = 0; v < 19; ++v) {
    EXPECT_LT((fit.positions[v] - before[v]).norm(), 1e-14) << v;
  }
}

TEST(FitRelaxationTest, MovesAPerturbedVertexHalfWayToItsRingCentroid) {
  FitCase fit = FlatHexagon();
  const VertexRings rings = fit.Rings(1);
  const uint32_t v = fit.Splitting(0, 0, 1);  // on a spoke: inner
  ASSERT_FALSE(rings.IsBoundary(v));
  fit.positions[v] += Vec3(0.12, 0.07, 0);
  fit.AnchorToClosest(19);
  const Vec3 start = fit.positions[v];
  const Vec3 centroid = RingCentroid(fit, rings, v);

  Relax(fit.state(), 1, rings);

  // relax_step 0.5 in the plane, which is the surface.
  const Vec3 expected = start + fit.options.relax_step * (centroid - start);
  EXPECT_LT((fit.positions[v] - expected).norm(), 1e-12);
  EXPECT_LT(fit.OffSurface(fit.positions[v]), 1e-15);
  EXPECT_EQ(
      fit.anchors[v].face,
      fit.surface->ClosestAnywhere(fit.positions[v], InputSurface::kNoFace)
          .face);
}

TEST(FitRelaxationTest, BoundaryLoopAndCoarserVerticesDoNotMove) {
  FitCase fit = FlatHexagon();
  const VertexRings rings = fit.Rings(1);
  // Perturbed: the centre (a base vertex), a new vertex on the remesh
  // boundary, and an inner new vertex said to lie on an input boundary loop.
  const uint32_t centre = 0;
  const uint32_t rim = fit.Splitting(0, 1, 2);
  const uint32_t on_loop = fit.Splitting(0, 0, 3);
  ASSERT_TRUE(rings.IsBoundary(rim));
  ASSERT_FALSE(rings.IsBoundary(on_loop));
  for (uint32_t v : {centre, rim, on_loop})
    fit.positions[v] += Vec3(0.1, -0.05, 0);
  fit.AnchorToClosest(19);
  fit.anchors[on_loop].loop = 0;
  fit.anchors[on_loop].s = 1.5;
  const std::vector<Vec3> before = fit.positions;

  Relax(fit.state(), 1, rings);

  for (uint32_t v : {centre, rim, on_loop})
    EXPECT_EQ(fit.positions[v], before[v]) << v;
  // Their neighbours, inner new vertices, did move toward them.
  const uint32_t neighbour = fit.Splitting(0, 0, 2);
  EXPECT_NE(fit.positions[neighbour], before[neighbour]);
}

TEST(FitRelaxationTest, KeepsVerticesOnACurvedSurface) {
  // Level 1 of the icosahedron placed on a finer sphere; one new vertex
  // pushed sideways along the surface.
  FitCase fit(testing::IcoSphere(3), testing::IcoSphere(0), 1);
  fit.PlaceAtMidpoints(0);
  for (uint32_t v = 12; v < 42; ++v) fit.positions[v].normalize();
  const uint32_t v = 20;
  fit.positions[v] = (fit.positions[v] + Vec3(0.08, 0.05, -0.06)).normalized();
  for (uint32_t u = 0; u < 42; ++u) {
    fit.positions[u] =
        fit.surface->ClosestAnywhere(fit.positions[u], InputSurface::kNoFace)
            .point;
  }
  fit.AnchorToClosest(42);
  const VertexRings rings = fit.Rings(1);
  // The centroid is inside the sphere: compare directions from the centre.
  const Vec3 centroid = RingCentroid(fit, rings, v).normalized();
  const double before = std::acos(fit.positions[v].normalized().dot(centroid));

  Relax(fit.state(), 1, rings);

  for (uint32_t u = 12; u < 42; ++u)
    EXPECT_LT(fit.OffSurface(fit.positions[u]), 1e-12) << u;
  const double after = std::acos(fit.positions[v].normalized().dot(centroid));
  EXPECT_LT(after, 0.7 * before);
}

}  // namespace
}  // namespace meshwave::remesh
