#include "remesh/fold_repair.h"

#include <gtest/gtest.h>

#include "codec/remesh/fit_cases_testonly.h"

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

}  // namespace
}  // namespace meshwave::remesh
