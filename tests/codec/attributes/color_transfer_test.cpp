// Colour transfer onto a remesh: exact on the original's own vertices and
// on linear gradients, per face at colour borders, finite on degenerate
// faces, independent of the thread count, and refusing colours that do not
// fit the mesh.
#include "pipeline/color_transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../metrics/test_meshes_testonly.h"

namespace meshwave {
namespace {

// One colour per vertex, every corner of the vertex using it.
CornerAttribute<Eigen::Vector4f> PerVertex(const TriMesh& mesh,
                                           const std::vector<Eigen::Vector4f>& values) {
  CornerAttribute<Eigen::Vector4f> color;
  color.values = values;
  color.faces = mesh.faces;
  return color;
}

// A colour that is an affine function of the position.
Eigen::Vector4f Gradient(const Vec3& p) {
  return {static_cast<float>(0.5 * p[0]), static_cast<float>(0.25 + 0.5 * p[1]),
          static_cast<float>(0.75 - 0.25 * p[0] - 0.25 * p[1]), 1.0f};
}

TEST(ColorTransferTest, GivesTheOriginalColoursOnItsOwnVertices) {
  const TriMesh mesh = testing::Icosphere(2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Eigen::Vector4f> values;
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    values.emplace_back(unit(rng), unit(rng), unit(rng), 1.0f);
  }
  auto out = TransferCornerColors(mesh.positions, mesh.faces, PerVertex(mesh, values),
                                  mesh.positions);
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  ASSERT_EQ(out->size(), mesh.positions.size());
  for (size_t v = 0; v < values.size(); ++v) {
    EXPECT_LT(((*out)[v] - values[v].head<3>().cast<double>()).cwiseAbs().maxCoeff(), 1e-12)
        << "vertex " << v;
  }
}

TEST(ColorTransferTest, PreservesALinearGradient) {
  // Midpoints of edges and random points above a flat patch: the
  // semi-regular vertices of the next level and a remesh's scattered ones.
  const TriMesh mesh = testing::GridPatch(6, 0, 0, 1);
  std::vector<Eigen::Vector4f> values;
  for (const Vec3& p : mesh.positions) values.push_back(Gradient(p));
  std::vector<Vec3> targets;
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      targets.push_back(0.5 * (mesh.positions[f[k]] + mesh.positions[f[(k + 1) % 3]]));
    }
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 500; ++i) targets.emplace_back(unit(rng), unit(rng), 0.01);
  auto out = TransferCornerColors(mesh.positions, mesh.faces, PerVertex(mesh, values), targets);
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  for (size_t i = 0; i < targets.size(); ++i) {
    const Vec3 on_surface(targets[i][0], targets[i][1], 0);
    // Float corner colours: exact up to their rounding.
    EXPECT_LT(((*out)[i] - Gradient(on_surface).head<3>().cast<double>()).cwiseAbs().maxCoeff(),
              1e-6)
        << "target " << i;
  }
}

TEST(ColorTransferTest, TakesEachFacesOwnCornersAtAColourBorder) {
  // Two triangles sharing the edge (1, 2); each has its own corner colours
  // there, as a texture-less colour border does.
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const std::vector<Face> faces = {{0, 1, 2}, {1, 3, 2}};
  CornerAttribute<Eigen::Vector4f> color;
  color.values = {{1, 0, 0, 1}, {0, 0, 1, 1}};
  color.faces = {{0, 0, 0}, {1, 1, 1}};
  auto out = TransferCornerColors(positions, faces, color,
                                  {{0.2, 0.2, 0.1}, {0.8, 0.8, -0.1}, {0.5, 0.5, 0}});
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  EXPECT_EQ((*out)[0], Vec3(1, 0, 0));
  EXPECT_EQ((*out)[1], Vec3(0, 0, 1));
  // On the border: one face's colour, not a blend of both.
  EXPECT_TRUE((*out)[2] == Vec3(1, 0, 0) || (*out)[2] == Vec3(0, 0, 1)) << (*out)[2].transpose();
}

TEST(ColorTransferTest, WeighsTheCornersOfTheNearestPoint) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_LT((ClosestBarycentric({0.5, 0.5, 3}, a, b, c) - Vec3(0.5, 0.25, 0.25)).norm(), 1e-15);
  // Beyond a corner and beyond an edge: the nearest point of the triangle.
  EXPECT_EQ(ClosestBarycentric({-1, -1, 0}, a, b, c), Vec3(1, 0, 0));
  EXPECT_EQ(ClosestBarycentric({3, -1, 0}, a, b, c), Vec3(0, 1, 0));
  EXPECT_LT((ClosestBarycentric({1, 1, 0}, a, b, c) - Vec3(0, 0.5, 0.5)).norm(), 1e-15);
  EXPECT_LT((ClosestBarycentric({2, 2, 0}, a, b, c) - Vec3(0, 0.5, 0.5)).norm(), 1e-15);
}

TEST(ColorTransferTest, DegenerateFacesWeighTheirLongestEdge) {
  // Collinear: c between a and b, so the triangle is the segment ab.
  const Vec3 w = ClosestBarycentric({0.25, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0.5, 0, 0});
  EXPECT_LT((w - Vec3(0.75, 0.25, 0)).norm(), 1e-15);
  // Two coincident corners: the edge to the third.
  const Vec3 v = ClosestBarycentric({0, 0.5, 0}, {0, 0, 0}, {0, 0, 0}, {0, 2, 0});
  EXPECT_DOUBLE_EQ(v.sum(), 1.0);
  EXPECT_LT((v - Vec3(0, 0.75, 0.25)).norm(), 1e-15);
  // All three coincident: an equal share each.
  EXPECT_EQ(ClosestBarycentric({1, 1, 1}, Vec3::Zero(), Vec3::Zero(), Vec3::Zero()),
            Vec3::Constant(1.0 / 3.0));
}

TEST(ColorTransferTest, StaysFiniteOnAMeshWithDegenerateFaces) {
  // A sliver (collinear) and a point-face beside a proper triangle.
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}};
  const std::vector<Face> faces = {{0, 1, 2}, {1, 3, 4}, {4, 4, 4}};
  CornerAttribute<Eigen::Vector4f> color;
  color.values = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}, {0, 0, 0, 1}};
  color.faces = faces;
  auto out = TransferCornerColors(positions, faces, color,
                                  {{2.5, 0.5, 0}, {3.5, 0, 0}, {0.25, 0.25, 0}});
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  for (const Vec3& rgb : *out) {
    EXPECT_TRUE(rgb.allFinite());
    EXPECT_GE(rgb.minCoeff(), 0.0);
    EXPECT_LE(rgb.maxCoeff(), 1.0);
  }
  // The sliver is its longest edge, from vertex 1 (green) to vertex 4
  // (black); x = 2.5 is three quarters of the way.
  EXPECT_LT(((*out)[0] - Vec3(0, 0.25, 0)).norm(), 1e-12);
  EXPECT_LT((*out)[1].norm(), 1e-12);  // beyond vertex 4: its black
}

TEST(ColorTransferTest, GivesTheSameColoursOnAnyThreadCount) {
  const TriMesh mesh = testing::Icosphere(3);
  std::vector<Eigen::Vector4f> values;
  for (const Vec3& p : mesh.positions) values.push_back(Gradient(p));
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Vec3> targets;
  for (int i = 0; i < 20000; ++i) {
    targets.push_back(Vec3(normal(rng), normal(rng), normal(rng)).normalized() * 1.01);
  }
  const auto color = PerVertex(mesh, values);
  auto one = TransferCornerColors(mesh.positions, mesh.faces, color, targets, 1);
  auto four = TransferCornerColors(mesh.positions, mesh.faces, color, targets, 4);
  ASSERT_TRUE(one.ok() && four.ok());
  EXPECT_EQ(*one, *four);
}

TEST(ColorTransferTest, RefusesColoursThatDoNotFitTheMesh) {
  const TriMesh mesh = testing::GridPatch(1, 0, 0, 1);
  const std::vector<Vec3> targets = {{0.5, 0.5, 0}};
  CornerAttribute<Eigen::Vector4f> none;
  EXPECT_EQ(TransferCornerColors(mesh.positions, mesh.faces, none, targets).status().code(),
            StatusCode::kInvalidArgument);
  CornerAttribute<Eigen::Vector4f> short_faces;
  short_faces.values = {{1, 1, 1, 1}};
  short_faces.faces = {{0, 0, 0}};
  const auto too_few = TransferCornerColors(mesh.positions, mesh.faces, short_faces, targets);
  EXPECT_EQ(too_few.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(too_few.status().message().find("1 colour corner triples for 2 faces"),
            std::string::npos)
      << too_few.status().message();
  CornerAttribute<Eigen::Vector4f> past = short_faces;
  past.faces = {{0, 0, 0}, {0, 1, 0}};
  EXPECT_FALSE(TransferCornerColors(mesh.positions, mesh.faces, past, targets).ok());
  short_faces.faces.push_back({0, 0, 0});
  EXPECT_FALSE(TransferCornerColors(mesh.positions, {}, short_faces, targets).ok());
  EXPECT_FALSE(TransferCornerColors(mesh.positions, mesh.faces, short_faces,
                                    {{std::nan(""), 0, 0}})
                   .ok());
  EXPECT_TRUE(TransferCornerColors(mesh.positions, mesh.faces, short_faces, targets).ok());
}

}  // namespace
}  // namespace meshwave
