#include "remesh/fold_repair.h"

#include <gtest/gtest.h>

#include "codec/remesh/fit_cases_testonly.h"
#include "remesh/fit_projection.h"
#include "remesh/qem_simplifier.h"
#include "remesh/remesh_quality.h"

namespace meshwave::remesh {
namespace {

using testing::FitCase;
using testing::FlatHexagon;

// The same with the middle of spoke 0-1 pushed past the middle of spoke
// 0-2: faces around it turn over.
FitCase FoldedHexagon() {
  FitCase fit = FlatHexagon();
  const uint32_t v = fit.Splitting(0, 0, 1);
  const uint32_t u = fit.Splitting(0, 0, 2);
  fit.positions[v] =
      fit.positions[u] + 0.3 * (fit.positions[u] - fit.positions[v]);
  fit.AnchorToClosest(19);
  return fit;
}

size_t FacesTurnedOver(const FitCase& fit) {
  size_t n = 0;
  for (const Vec3& normal : fit.FaceNormals(1)) n += normal.z() <= 0 ? 1 : 0;
  return n;
}

size_t VerticesMoved(const std::vector<Vec3>& before,
                     const std::vector<Vec3>& after) {
  size_t n = 0;
  for (size_t v = 0; v < before.size(); ++v) n += before[v] != after[v] ? 1 : 0;
  return n;
}

TEST(FoldRepairTest, LeavesACleanLevelUntouched) {
  FitCase fit = FlatHexagon();
  ASSERT_EQ(FacesTurnedOver(fit), 0u);
  const std::vector<Vec3> before = fit.positions;
  EXPECT_EQ(FoldRepair(fit.state()).Run(1, fit.Rings(1)), 0u);
  EXPECT_EQ(fit.positions, before);
  EXPECT_EQ(fit.stats.repair_moves, 0u);
}

TEST(FoldRepairTest, UntanglingUnfoldsAFoldedVertexOnTheSurface) {
  FitCase fit = FoldedHexagon();
  ASSERT_GT(FacesTurnedOver(fit), 0u);
  const std::vector<Vec3> before = fit.positions;

  EXPECT_EQ(FoldRepair(fit.state()).UntangleLevel(1, fit.Rings(1)), 0u);

  EXPECT_EQ(FacesTurnedOver(fit), 0u);
  for (const Vec3& p : fit.positions) EXPECT_LT(fit.OffSurface(p), 1e-12);
  // Only vertices of bad faces move: never the base.
  for (uint32_t v = 0; v < 7; ++v) EXPECT_EQ(fit.positions[v], before[v]) << v;
  // Every move counted (a vertex may move in several rounds).
  const size_t moved = VerticesMoved(before, fit.positions);
  EXPECT_GT(moved, 0u);
  EXPECT_GE(fit.stats.repair_moves, moved);
}

TEST(FoldRepairTest, FixFoldsAloneUnfoldsAFoldedVertex) {
  FitCase fit = FoldedHexagon();
  fit.options.repair_rounds = 0;  // no untangling rounds: FixFolds only
  ASSERT_GT(FacesTurnedOver(fit), 0u);
  const std::vector<Vec3> before = fit.positions;

  EXPECT_EQ(FoldRepair(fit.state()).Run(1, fit.Rings(1)), 0u);

  EXPECT_EQ(FacesTurnedOver(fit), 0u);
  const size_t moved = VerticesMoved(before, fit.positions);
  EXPECT_GT(moved, 0u);
  EXPECT_GE(fit.stats.repair_moves, moved);
}

TEST(FoldRepairTest, LeavesBoundaryVerticesOfTheRemeshWhereTheyAre) {
  FitCase fit = FoldedHexagon();
  const VertexRings rings = fit.Rings(1);
  const std::vector<Vec3> before = fit.positions;
  FoldRepair(fit.state()).Run(1, rings);
  // Not on an input boundary loop: nothing to slide along.
  for (uint32_t v = 0; v < 19; ++v) {
    if (rings.IsBoundary(v)) {
      EXPECT_EQ(fit.positions[v], before[v]) << v;
    }
  }
}

TEST(FoldRepairTest, SlidesABoundaryVertexAlongAJaggedInputBoundary) {
  // Input: the square [0, 2]^2 with a notch x in [1, 1.5], y in [0, 1.5]
  // cut into its bottom side. Base: the corners (0, 0), (2, 0), (0, 2).
  // Level 1 puts the middle of the bottom edge at the arc-length midpoint
  // of the notched stretch, the notch's top corner (1, 1.5), in line with
  // the other two new vertices: the middle face has no area, and only
  // boundary vertices (which slide along the loop) can fix it.
  TriMesh input = testing::FlatGrid(4, 0, 0, 2);
  std::vector<Face> kept;
  for (size_t f = 0; f < input.faces.size(); ++f) {
    const size_t cell = f / 2, i = cell % 4, j = cell / 4;
    if (!(i == 2 && j < 3)) kept.push_back(input.faces[f]);
  }
  input.faces = kept;
  SimplifiedMesh base;
  base.mesh.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  base.mesh.faces = {{0, 1, 2}};
  base.source_vertex = {0, 4, 20};
  base.component = {0, 0, 0};
  FitCase fit(input, base.mesh, 1);
  std::vector<Vec3> base_positions;
  std::vector<SurfaceAnchor> base_anchors;
  PlaceBaseVertices(base, *fit.surface, {}, base_positions, base_anchors);
  std::copy(base_positions.begin(), base_positions.end(),
            fit.positions.begin());
  std::copy(base_anchors.begin(), base_anchors.end(), fit.anchors.begin());
  fit.PlaceAtMidpoints(0);
  PlaceNewVertices(fit.state(), 0);
  const uint32_t bottom = fit.Splitting(0, 0, 1);
  ASSERT_LT((fit.positions[bottom] - Vec3(1, 1.5, 0)).norm(), 1e-12);
  const Face middle = {bottom, fit.Splitting(0, 1, 2), fit.Splitting(0, 2, 0)};
  ASSERT_LT(Compactness(fit.positions[middle[0]], fit.positions[middle[1]],
                        fit.positions[middle[2]]),
            kDegenerateCompactness);
  const std::vector<SurfaceAnchor> before = fit.anchors;
  fit.options.repair_rounds = 0;

  EXPECT_EQ(FoldRepair(fit.state()).Run(1, fit.Rings(1)), 0u);

  EXPECT_GT(Compactness(fit.positions[middle[0]], fit.positions[middle[1]],
                        fit.positions[middle[2]]),
            kDegenerateCompactness);
  EXPECT_EQ(FacesTurnedOver(fit), 0u);
  // Whatever moved slid along the loop: it is where its arc length says.
  size_t slid = 0;
  for (uint32_t v = 0; v < 6; ++v) {
    ASSERT_EQ(fit.anchors[v].loop, 0u) << v;
    EXPECT_EQ(fit.positions[v],
              fit.surface->loops().At(0, fit.anchors[v].s).position)
        << v;
    slid += fit.anchors[v].s != before[v].s ? 1 : 0;
  }
  EXPECT_GT(slid, 0u);
  EXPECT_EQ(fit.stats.repair_moves, slid);
}

}  // namespace
}  // namespace meshwave::remesh
