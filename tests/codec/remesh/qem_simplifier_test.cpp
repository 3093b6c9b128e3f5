#include "remesh/qem_simplifier.h"

#include <gtest/gtest.h>

#include "codec/remesh/manifold_checks_testonly.h"
#include "codec/remesh/remesh_meshes_testonly.h"
#include "codec/test_meshes.h"
#include "remesh/boundary_loops.h"
#include "remesh/components.h"
#include "semiregular/vertex_rings.h"
#include "meshwave/mesh_stats.h"

namespace meshwave::remesh {
namespace {

using testing::Combined;
using testing::ExpectOrientedManifold;
using testing::Icosahedron;
using testing::Torus;
using testing::Translated;
using testing::UvSphere;
using testing::WavySheet;

SimplifiedMesh Simplify(const TriMesh& mesh, size_t target,
                        uint32_t min_faces = 8) {
  const Components components = LabelComponents(mesh);
  SimplifyOptions options;
  options.target_faces = target;
  options.min_faces.assign(components.count, min_faces);
  return SimplifyByEdgeCollapse(mesh, components, options);
}

TEST(QemSimplifierTest, ReachesTheTargetOnASphere) {
  const TriMesh sphere = UvSphere(24, 32);
  const SimplifiedMesh base = Simplify(sphere, 200);
  EXPECT_LE(base.mesh.faces.size(), 200u);
  EXPECT_GE(base.mesh.faces.size(), 190u);
  ExpectOrientedManifold(base.mesh);
  const MeshStats stats = ComputeStats(base.mesh);
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.genus, 0);
  // Quadric placement keeps the vertices near the unit sphere.
  for (const Vec3& p : base.mesh.positions) EXPECT_NEAR(p.norm(), 1.0, 0.03);
}

TEST(QemSimplifierTest, KeepsTheGenusOfATorus) {
  const SimplifiedMesh base = Simplify(Torus(48, 24), 60);
  ExpectOrientedManifold(base.mesh);
  const MeshStats stats = ComputeStats(base.mesh);
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.genus, 1);
  EXPECT_LE(base.mesh.faces.size(), 120u);
}

TEST(QemSimplifierTest, KeepsBoundaryVerticesOnTheInputBoundary) {
  const TriMesh sheet = WavySheet(30, 10);
  const BoundaryLoops input_loops(sheet);
  ASSERT_EQ(input_loops.count(), 2u);
  const SimplifiedMesh base = Simplify(sheet, 120);
  ExpectOrientedManifold(base.mesh);
  const MeshStats stats = ComputeStats(base.mesh);
  EXPECT_EQ(stats.boundary_loops, 2u);
  const BoundaryLoops base_loops(base.mesh);
  ASSERT_EQ(base_loops.count(), 2u);
  for (uint32_t v = 0; v < base.mesh.positions.size(); ++v) {
    if (base_loops.Locate(v).loop == BoundaryLoops::kNone) continue;
    const uint32_t source = base.source_vertex[v];
    ASSERT_NE(source, SimplifiedMesh::kNone) << v;
    EXPECT_NE(input_loops.Locate(source).loop, BoundaryLoops::kNone) << v;
    EXPECT_EQ(base.mesh.positions[v], sheet.positions[source]);
  }
}

TEST(QemSimplifierTest, LeavesEveryComponentItsFloor) {
  // A big sphere and a small one: the cheap small one stops at its floor.
  const TriMesh mesh = Combined(
      UvSphere(24, 32), Translated(UvSphere(10, 12, 0.05), Vec3(3, 0, 0)));
  const SimplifiedMesh base = Simplify(mesh, 100, 16);
  const Components components = LabelComponents(base.mesh);
  ASSERT_EQ(components.count, 2u);
  std::vector<size_t> faces(2, 0);
  for (uint32_t c : components.of_face) ++faces[c];
  EXPECT_GE(faces[0], 15u);
  EXPECT_GE(faces[1], 15u);
  for (size_t v = 0; v < base.component.size(); ++v) {
    EXPECT_EQ(base.component[v], components.of_vertex[v]);
  }
}

TEST(QemSimplifierTest, NeverGoesBelowATetrahedron) {
  const SimplifiedMesh base = Simplify(Icosahedron(), 1, 0);
  ExpectOrientedManifold(base.mesh);
  EXPECT_GE(base.mesh.faces.size(), 4u);
  EXPECT_TRUE(ComputeStats(base.mesh).closed);
}

TEST(QemSimplifierTest, LeavesAMeshAtItsTargetUntouched) {
  const TriMesh sphere = UvSphere(6, 8);
  const SimplifiedMesh base = Simplify(sphere, sphere.faces.size());
  EXPECT_EQ(base.collapses, 0u);
  EXPECT_EQ(base.mesh.faces.size(), sphere.faces.size());
}

}  // namespace
}  // namespace meshwave::remesh
