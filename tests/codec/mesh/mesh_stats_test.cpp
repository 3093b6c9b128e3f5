#include <gtest/gtest.h>

#include <vector>

#include "codec/mesh/mesh_builders_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_stats.h"

namespace meshwave {
namespace {

// An n-by-m grid with opposite sides identified: a closed torus.
TriMesh Torus(uint32_t n, uint32_t m) {
  TriMesh mesh;
  for (uint32_t j = 0; j < m; ++j) {
    for (uint32_t i = 0; i < n; ++i) mesh.positions.emplace_back(i, j, 0.0);
  }
  auto at = [n, m](uint32_t i, uint32_t j) { return (j % m) * n + (i % n); };
  for (uint32_t j = 0; j < m; ++j) {
    for (uint32_t i = 0; i < n; ++i) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

TEST(MeshStatsTest, DescribesAClosedTetrahedron) {
  MeshStats s = ComputeStats(testing::Tetrahedron());
  EXPECT_EQ(s.vertices, 4u);
  EXPECT_EQ(s.faces, 4u);
  EXPECT_EQ(s.edges, 6u);
  EXPECT_EQ(s.boundary_edges, 0u);
  EXPECT_EQ(s.boundary_loops, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.inconsistently_oriented_edges, 0u);
  EXPECT_TRUE(s.manifold);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshStatsTest, DescribesAnOpenDisc) {
  MeshStats s = ComputeStats(testing::Grid(3));
  EXPECT_EQ(s.vertices, 16u);
  EXPECT_EQ(s.boundary_edges, 12u);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_TRUE(s.manifold);
  EXPECT_FALSE(s.closed);
  EXPECT_EQ(s.euler_characteristic, 1);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshStatsTest, FindsGenusOneOnATorus) {
  MeshStats s = ComputeStats(Torus(6, 5));
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.euler_characteristic, 0);
  EXPECT_EQ(s.genus, 1);
}

TEST(MeshStatsTest, CountsTwoLoopsOnAnAnnulus) {
  // A 4x4 grid without its two middle squares: one outer and one inner loop.
  TriMesh mesh = testing::Grid(4);
  TriMesh annulus = mesh;
  annulus.faces.clear();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    size_t square = f / 2, x = square % 4, y = square / 4;
    if ((x == 1 || x == 2) && (y == 1 || y == 2)) continue;
    annulus.faces.push_back(mesh.faces[f]);
  }
  MeshStats s = ComputeStats(annulus);
  EXPECT_EQ(s.boundary_loops, 2u);
  EXPECT_EQ(s.boundary_edges, 16u + 8u);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshStatsTest, CountsComponentsAndUnreferencedVertices) {
  TriMesh mesh = testing::Tetrahedron();
  mesh.positions.emplace_back(7, 7, 7);  // unreferenced
  TriMesh second = testing::Tetrahedron();
  const uint32_t offset = static_cast<uint32_t>(mesh.positions.size());
  for (const Vec3& p : second.positions)
    mesh.positions.push_back(p + Vec3(5, 0, 0));
  for (Face f : second.faces)
    mesh.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  MeshStats s = ComputeStats(mesh);
  EXPECT_EQ(s.vertices, 8u);
  EXPECT_EQ(s.unreferenced_vertices, 1u);
  EXPECT_EQ(s.components, 2u);
  EXPECT_EQ(s.euler_characteristic, 4);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshStatsTest, FlagsAnEdgeSharedByThreeFaces) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0),
                    Vec3(0, 0, 1)};
  mesh.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  MeshStats s = ComputeStats(mesh);
  EXPECT_EQ(s.non_manifold_edges, 1u);
  EXPECT_FALSE(s.manifold);
  EXPECT_FALSE(s.closed);
  EXPECT_EQ(s.genus, -1);
}

TEST(MeshStatsTest, FlagsABowtieVertex) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0),
                    Vec3(-1, -1, 0)};
  mesh.faces = {{0, 1, 2}, {0, 3, 4}};
  MeshStats s = ComputeStats(mesh);
  EXPECT_EQ(s.non_manifold_vertices, 1u);
  EXPECT_EQ(s.non_manifold_edges, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_FALSE(s.manifold);
  EXPECT_EQ(s.genus, -1);
}

TEST(MeshStatsTest, CountsInconsistentlyOrientedEdges) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  mesh.faces = {{0, 1, 2}, {1, 2, 3}};  // both run 1->2
  MeshStats s = ComputeStats(mesh);
  EXPECT_EQ(s.inconsistently_oriented_edges, 1u);
  EXPECT_EQ(s.edges, 5u);
  EXPECT_EQ(s.boundary_edges, 4u);
  mesh.faces[1] = {2, 1, 3};
  EXPECT_EQ(ComputeStats(mesh).inconsistently_oriented_edges, 0u);
}

TEST(MeshStatsTest, SurvivesDegenerateFacesAndEmptyMeshes) {
  TriMesh mesh = testing::Tetrahedron();
  mesh.faces.push_back({0, 0, 1});
  MeshStats s = ComputeStats(mesh);
  EXPECT_EQ(s.faces, 5u);
  EXPECT_EQ(ComputeStats(TriMesh{}).vertices, 0u);
}

TEST(MeshStatsTest, HandlesALargeGrid) {
  MeshStats s = ComputeStats(testing::Grid(370));  // 273,800 faces
  EXPECT_EQ(s.faces, 273800u);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(s.genus, 0);
}

}  // namespace
}  // namespace meshwave
