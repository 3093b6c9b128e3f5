#include "remesh/boundary_loops.h"

#include <gtest/gtest.h>

#include "codec/remesh/remesh_meshes_testonly.h"
#include "codec/test_meshes.h"

namespace meshwave::remesh {
namespace {

// A flat square [0, 2]² made of two triangles, facing +z: one loop of
// length 8 running counter-clockwise.
TriMesh Square() {
  TriMesh m;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(BoundaryLoopsTest, ParametrisesALoopByArcLength) {
  const TriMesh square = Square();
  const BoundaryLoops loops(square);
  ASSERT_EQ(loops.count(), 1u);
  EXPECT_DOUBLE_EQ(loops.Length(0), 8.0);
  const BoundaryLoops::Location a = loops.Locate(0);
  const BoundaryLoops::Location b = loops.Locate(1);
  ASSERT_EQ(a.loop, 0u);
  // Counter-clockwise: 1 comes 2 after 0 along the loop.
  EXPECT_DOUBLE_EQ(std::fmod(b.s - a.s + 8, 8), 2.0);
  const BoundaryLoops::Point mid = loops.At(0, loops.Midway(0, a.s, b.s));
  EXPECT_TRUE(mid.position.isApprox(Vec3(1, 0, 0)));
  EXPECT_EQ(mid.face, 0u);
}

TEST(BoundaryLoopsTest, MidwayWrapsAroundTheStart) {
  const TriMesh square = Square();
  const BoundaryLoops loops(square);
  const double s3 = loops.Locate(3).s, s0 = loops.Locate(0).s;
  const BoundaryLoops::Point mid = loops.At(0, loops.Midway(0, s3, s0));
  EXPECT_TRUE(mid.position.isApprox(Vec3(0, 1, 0)));
  // At() takes arc lengths modulo the length.
  EXPECT_TRUE(loops.At(0, s0 + 16).position.isApprox(Vec3(0, 0, 0)));
}

TEST(BoundaryLoopsTest, FindsNoLoopOnAClosedMesh) {
  const BoundaryLoops loops(testing::Icosahedron());
  EXPECT_EQ(loops.count(), 0u);
  EXPECT_EQ(loops.Locate(0).loop, BoundaryLoops::kNone);
}

TEST(BoundaryLoopsTest, FindsTheOuterLoopAndTheHole) {
  const TriMesh sheet = testing::WavySheet(12, 4);
  const BoundaryLoops loops(sheet);
  ASSERT_EQ(loops.count(), 2u);
  // The outer loop is longer than 8 (the wavy square's flat perimeter).
  const double longer = std::max(loops.Length(0), loops.Length(1));
  const double shorter = std::min(loops.Length(0), loops.Length(1));
  EXPECT_GT(longer, 8.0);
  EXPECT_GT(shorter, 2.0);
  EXPECT_LT(shorter, 4.0);
}

}  // namespace
}  // namespace meshwave::remesh
