#include <gtest/gtest.h>

#include <vector>

#include "codec/mesh/mesh_builders_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_stats.h"

namespace meshwave {
namespace {

TEST(MeshCleanTest, LeavesACleanMeshAlone) {
  TriMesh mesh = testing::Grid(3);
  const TriMesh before = mesh;
  CleanReport report = CleanMesh(mesh);
  EXPECT_EQ(mesh.positions, before.positions);
  EXPECT_EQ(mesh.faces, before.faces);
  EXPECT_EQ(report.merged_vertices + report.degenerate_faces +
                report.duplicate_faces + report.unreferenced_vertices +
                report.zero_area_faces,
            0u);
}

TEST(MeshCleanTest, MergesBitIdenticalVerticesKeepingTheFirst) {
  TriMesh mesh;
  // Two triangles sharing an edge, stored with the shared corners repeated.
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                    Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  mesh.faces = {{0, 1, 2}, {3, 4, 5}};
  CleanReport report = CleanMesh(mesh);
  EXPECT_EQ(report.merged_vertices, 2u);
  EXPECT_EQ(report.unreferenced_vertices, 0u);
  EXPECT_EQ(mesh.positions, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0),
                                               Vec3(0, 1, 0), Vec3(1, 1, 0)}));
  EXPECT_EQ(mesh.faces, (std::vector<Face>{{0, 1, 2}, {1, 3, 2}}));
  EXPECT_EQ(ComputeStats(mesh).boundary_loops, 1u);
}

TEST(MeshCleanTest, DoesNotMergeNegativeAndPositiveZero) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(-0.0, 0, 0), Vec3(1, 0, 0),
                    Vec3(0, 1, 0)};
  mesh.faces = {{0, 2, 3}, {1, 2, 3}};
  EXPECT_EQ(CleanMesh(mesh).merged_vertices, 0u);
}

TEST(MeshCleanTest, DropsDegenerateAndDuplicateFaces) {
  TriMesh mesh = testing::Tetrahedron();
  mesh.faces.push_back({1, 1, 2});  // repeated corner
  mesh.faces.push_back({2, 0, 1});  // {0,2,1} rotated
  mesh.faces.push_back({3, 1, 0});  // {0,1,3} reversed
  CleanReport report = CleanMesh(mesh);
  EXPECT_EQ(report.degenerate_faces, 1u);
  EXPECT_EQ(report.duplicate_faces, 2u);
  EXPECT_EQ(mesh.faces, testing::Tetrahedron().faces);
}

TEST(MeshCleanTest, DropsUnreferencedVerticesAndRemapsStably) {
  TriMesh mesh;
  mesh.positions = {Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(8, 8, 8), Vec3(1, 0, 0),
                    Vec3(0, 1, 0)};
  mesh.faces = {{1, 3, 4}};
  CleanReport report = CleanMesh(mesh);
  EXPECT_EQ(report.unreferenced_vertices, 2u);
  EXPECT_EQ(mesh.positions,
            (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}));
  EXPECT_EQ(mesh.faces, (std::vector<Face>{{0, 1, 2}}));
}

TEST(MeshCleanTest, CountsZeroAreaFacesButKeepsThem) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(0, 1, 0)};
  mesh.faces = {{0, 1, 2}, {0, 1, 3}};
  CleanReport report = CleanMesh(mesh);
  EXPECT_EQ(report.zero_area_faces, 1u);
  EXPECT_EQ(mesh.faces.size(), 2u);
}

TEST(MeshCleanTest, HonoursDisabledSteps) {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0),
                    Vec3(5, 5, 5)};
  mesh.faces = {{0, 1, 2}, {3, 1, 2}, {0, 0, 1}, {2, 1, 0}};
  CleanOptions options;
  options.merge_duplicate_vertices = false;
  options.drop_degenerate_faces = false;
  options.drop_duplicate_faces = false;
  options.drop_unreferenced_vertices = false;
  const TriMesh before = mesh;
  CleanReport report = CleanMesh(mesh, options);
  EXPECT_EQ(mesh.positions, before.positions);
  EXPECT_EQ(mesh.faces, before.faces);
  EXPECT_EQ(report.unreferenced_vertices, 1u);  // found, left alone
  EXPECT_EQ(report.merged_vertices, 0u);

  options.merge_duplicate_vertices = true;
  report = CleanMesh(mesh, options);
  EXPECT_EQ(report.merged_vertices, 1u);
  EXPECT_EQ(mesh.positions.size(),
            4u);  // the duplicate goes, the unreferenced stays
  EXPECT_EQ(mesh.faces[1], (Face{0, 1, 2}));
}

}  // namespace
}  // namespace meshwave
