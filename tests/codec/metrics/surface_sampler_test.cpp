#include "metrics/surface_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "metrics/closest_point_triangle.h"
#include "test_meshes_testonly.h"

namespace meshwave::metrics {
namespace {

TEST(SurfaceSamplerTest, UnitIntervalMapsTheTop53BitsToHalfOpenInterval) {
  EXPECT_EQ(UnitInterval(0), 0.0);
  EXPECT_EQ(UnitInterval(uint64_t{1} << 63), 0.5);
  EXPECT_LT(UnitInterval(std::numeric_limits<uint64_t>::max()), 1.0);
  EXPECT_EQ(UnitInterval(std::numeric_limits<uint64_t>::max()),
            1.0 - 0x1.0p-53);
}

TEST(SurfaceSamplerTest, FaceCountsSpreadTheTotalByAreaWithAtLeastOneEach) {
  TriMesh mesh = testing::Icosphere(2);
  // Stretch to make face areas unequal.
  for (Vec3& p : mesh.positions) p.x() *= 3;
  double total_area = 0;
  for (const Face& f : mesh.faces) total_area += FaceArea(mesh, f);
  const uint64_t total = 10007;
  FaceSampleCounts counts(mesh, total);
  uint64_t sum = 0;
  for (const Face& f : mesh.faces) {
    const double area = FaceArea(mesh, f);
    const uint64_t n = counts.Next(area);
    EXPECT_GE(n, 1u);
    EXPECT_NEAR(static_cast<double>(n), total * area / total_area, 1.0);
    sum += n;
  }
  EXPECT_EQ(sum, total);
}

TEST(SurfaceSamplerTest, TinyFacesStillGetOneSampleEach) {
  TriMesh mesh = testing::GridPatch(1, 0, 0, 1);  // two large faces
  mesh.positions.push_back({2, 0, 0});
  mesh.positions.push_back({2 + 1e-9, 0, 0});
  mesh.positions.push_back({2, 1e-9, 0});
  mesh.faces.push_back({4, 5, 6});
  FaceSampleCounts counts(mesh, 100);
  EXPECT_GE(counts.Next(FaceArea(mesh, mesh.faces[0])), 49u);
  EXPECT_GE(counts.Next(FaceArea(mesh, mesh.faces[1])), 49u);
  EXPECT_EQ(counts.Next(FaceArea(mesh, mesh.faces[2])), 1u);
}

TEST(SurfaceSamplerTest, AllDegenerateFacesShareTheSamplesEqually) {
  TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  mesh.faces = {{0, 1, 2}, {2, 1, 0}};
  FaceSampleCounts counts(mesh, 10);
  EXPECT_EQ(counts.Next(0), 5u);
  EXPECT_EQ(counts.Next(0), 5u);
}

TEST(SurfaceSamplerTest, VisitsReferencedVerticesOnceAndPointsOnFaces) {
  TriMesh mesh = testing::Icosphere(1);
  mesh.positions.push_back({10, 10, 10});  // unreferenced: never sampled
  size_t on_vertex = 0;
  const uint64_t n = VisitSurfaceSamples(mesh, 1000, 5, [&](const Vec3& p) {
    ASSERT_LT(p.norm(), 1 + 1e-12);
    double best = std::numeric_limits<double>::infinity();
    for (const Face& f : mesh.faces) {
      best = std::min(best, ClosestPointOnTriangle(p, mesh.positions[f[0]],
                                                   mesh.positions[f[1]],
                                                   mesh.positions[f[2]])
                                .distance_squared);
    }
    ASSERT_LT(best, 1e-28);
    if (std::abs(p.norm() - 1) < 1e-12) ++on_vertex;
  });
  EXPECT_EQ(on_vertex, mesh.positions.size() - 1);
  EXPECT_EQ(n, mesh.positions.size() - 1 + 1000);
}

TEST(SurfaceSamplerTest, SameSeedSameSamplesOtherSeedOthers) {
  const TriMesh mesh = testing::GridPatch(3, 0, 0, 1);
  std::vector<Vec3> first, second, other;
  VisitSurfaceSamples(mesh, 50, 9, [&](const Vec3& p) { first.push_back(p); });
  VisitSurfaceSamples(mesh, 50, 9, [&](const Vec3& p) { second.push_back(p); });
  VisitSurfaceSamples(mesh, 50, 10, [&](const Vec3& p) { other.push_back(p); });
  EXPECT_EQ(first, second);
  ASSERT_EQ(first.size(), other.size());
  EXPECT_NE(first, other);
}

}  // namespace
}  // namespace meshwave::metrics
