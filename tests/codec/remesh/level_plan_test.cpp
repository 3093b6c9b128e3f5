#include "remesh/level_plan.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meshwave::remesh {
namespace {

// Vertices of the finest level of a closed mesh: V_0 + F_0 (4^J - 1) / 2.
double FinestVertices(const LevelPlan& plan) {
  const double f0 = static_cast<double>(plan.base_faces);
  return f0 / 2 + 2 + f0 * (std::pow(4.0, plan.levels) - 1) / 2;
}

TEST(LevelPlanTest, MatchesTheInputSizeAtTheFinestLevel) {
  for (size_t vertices : {1000u, 4706u, 35000u, 134345u, 537000u, 3000000u}) {
    auto plan = PlanLevels(vertices, -1, -1);
    ASSERT_TRUE(plan.ok());
    const double ratio = FinestVertices(*plan) / static_cast<double>(vertices);
    EXPECT_GT(ratio, 0.9) << vertices;
    EXPECT_LT(ratio, 1.1) << vertices;
    EXPECT_GE(plan->levels, 2) << vertices;
    EXPECT_LE(plan->levels, 5) << vertices;
  }
}

TEST(LevelPlanTest, PrefersThreeOrFourLevelsForScans) {
  EXPECT_EQ(PlanLevels(35000, -1, -1)->levels, 3);   // bunny
  EXPECT_EQ(PlanLevels(134345, -1, -1)->levels, 4);  // igea
  EXPECT_EQ(PlanLevels(537000, -1, -1)->levels, 4);  // igea subdivided
  EXPECT_EQ(PlanLevels(4706, -1, -1)->levels, 2);    // too small for 3
}

TEST(LevelPlanTest, KeepsWhatTheUserAsked) {
  auto plan = PlanLevels(50000, 2, 300);
  ASSERT_TRUE(plan.ok());
  EXPECT_EQ(plan->levels, 2);
  EXPECT_EQ(plan->base_faces, 300u);
  // Levels given: base faces follow the input size.
  EXPECT_EQ(PlanLevels(50000, 3, -1)->base_faces, 1563u);  // 100000 / 64
  // Base faces given: the levels that best match the input size.
  EXPECT_EQ(PlanLevels(50000, -1, 100)->levels, 5);
}

TEST(LevelPlanTest, RejectsImpossibleRequests) {
  EXPECT_EQ(PlanLevels(1000, 0, -1).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(PlanLevels(1000, 9, -1).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(PlanLevels(1000, -1, 0).status().code(),
            StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace meshwave::remesh
