#include "remesh/manifold_repair.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "codec/remesh/manifold_checks_testonly.h"
#include "codec/remesh/remesh_meshes_testonly.h"
#include "codec/test_meshes.h"
#include "remesh/components.h"
#include "semiregular/vertex_rings.h"
#include "meshwave/mesh_stats.h"

namespace meshwave::remesh {
namespace {

using testing::ExpectOrientedManifold;
using testing::Icosahedron;
using testing::UvSphere;

Face Rotated(Face f) {
  std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  return f;
}

TEST(ManifoldRepairTest, LeavesAnOrientedManifoldAlone) {
  TriMesh mesh = UvSphere(6, 8);
  const TriMesh before = mesh;
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(mesh.positions, before.positions);
  EXPECT_EQ(mesh.faces, before.faces);
  EXPECT_EQ(report.added_vertices, 0u);
  EXPECT_EQ(report.reoriented_faces, 0u);
  EXPECT_EQ(report.non_manifold_edges, 0u);
}

TEST(ManifoldRepairTest, SplitsAVertexJoiningTwoFans) {
  // Two triangles touching at vertex 0 only (a bow tie).
  TriMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  mesh.faces = {{0, 1, 2}, {0, 3, 4}};
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(report.non_manifold_vertices, 1u);
  EXPECT_EQ(report.added_vertices, 1u);
  ASSERT_EQ(mesh.positions.size(), 6u);
  EXPECT_EQ(mesh.positions[5], mesh.positions[0]);  // a copy, same place
  ExpectOrientedManifold(mesh);
  EXPECT_EQ(LabelComponents(mesh).count, 2u);
}

TEST(ManifoldRepairTest, CutsAnEdgeSharedByThreeFaces) {
  TriMesh mesh;
  mesh.positions = {
      {0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}, {0.5, 0, 1}};
  mesh.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(report.non_manifold_edges, 1u);
  ExpectOrientedManifold(mesh);
  EXPECT_EQ(mesh.faces.size(), 3u);  // every face is kept
}

TEST(ManifoldRepairTest, TurnsOverTheMinorityOfInconsistentFaces) {
  TriMesh mesh = Icosahedron();
  const TriMesh original = mesh;
  for (size_t f : {0, 7, 13}) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(report.reoriented_faces, 3u);
  EXPECT_GT(report.misoriented_edges, 0u);
  EXPECT_EQ(report.added_vertices, 0u);
  ExpectOrientedManifold(mesh);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    EXPECT_EQ(Rotated(mesh.faces[f]), Rotated(original.faces[f])) << f;
  }
}

TEST(ManifoldRepairTest, KeepsTheMajorityOrientationOfAComponent) {
  TriMesh mesh = Icosahedron();
  for (size_t f = 2; f < mesh.faces.size(); ++f) {
    std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  }
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(report.reoriented_faces, 2u);
  ExpectOrientedManifold(mesh);
}

TEST(ManifoldRepairTest, CutsAMoebiusBandOpen) {
  // A strip of n quads whose ends are glued with a half twist.
  const int n = 12;
  TriMesh mesh;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * std::numbers::pi * i / n;
    for (int side : {-1, 1}) {
      const double w = 0.3 * side;
      mesh.positions.emplace_back((1 + w * std::cos(u / 2)) * std::cos(u),
                                  (1 + w * std::cos(u / 2)) * std::sin(u),
                                  w * std::sin(u / 2));
    }
  }
  for (int i = 0; i < n; ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 1;
    uint32_t c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the twist
    mesh.faces.push_back({a, c, d});
    mesh.faces.push_back({a, d, b});
  }
  const RepairReport report = RepairManifold(mesh);
  EXPECT_GE(report.non_orientable_cuts, 1u);
  ExpectOrientedManifold(mesh);
}

TEST(ManifoldRepairTest, SeparatesTwoSpheresTouchingAtAPoint) {
  // The north pole of the second sphere is the south pole of the first.
  TriMesh a = UvSphere(6, 8);
  TriMesh b = UvSphere(6, 8, 1.0, Vec3(0, 0, -2));
  const auto south = static_cast<uint32_t>(a.positions.size() - 1);
  TriMesh mesh = a;
  const auto offset = static_cast<uint32_t>(a.positions.size());
  mesh.positions.insert(mesh.positions.end(), b.positions.begin() + 1,
                        b.positions.end());
  for (Face f : b.faces) {
    for (uint32_t& v : f) v = v == 0 ? south : v + offset - 1;
    mesh.faces.push_back(f);
  }
  ASSERT_FALSE(ComputeStats(mesh).manifold);
  const RepairReport report = RepairManifold(mesh);
  EXPECT_EQ(report.non_manifold_vertices, 1u);
  ExpectOrientedManifold(mesh);
  EXPECT_EQ(LabelComponents(mesh).count, 2u);
}

}  // namespace
}  // namespace meshwave::remesh
