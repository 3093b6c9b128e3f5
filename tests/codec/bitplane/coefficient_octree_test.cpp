#include "bitplane/coefficient_octree.h"

#include <gtest/gtest.h>

#include <bit>
#include <random>
#include <set>

#include "codec/test_meshes.h"

namespace meshwave {
namespace {

void ExpectPartition(const CoefficientOctree& tree, const OctreeNode& node,
                     std::vector<int>& seen) {
  if (tree.IsLeaf(node)) {
    for (uint32_t i = node.begin; i < node.end; ++i) ++seen[tree.At(i)];
    return;
  }
  std::array<OctreeNode, 8> children;
  const int n = tree.Children(node, children);
  ASSERT_GE(n, 1);
  ASSERT_LE(n, 8);
  uint32_t at = node.begin;
  for (int c = 0; c < n; ++c) {
    EXPECT_EQ(children[c].begin, at);
    EXPECT_GT(children[c].end, children[c].begin);
    EXPECT_EQ(children[c].depth, node.depth + 1);
    at = children[c].end;
    ExpectPartition(tree, children[c], seen);
  }
  EXPECT_EQ(at, node.end);
}

TEST(CoefficientOctreeTest, CellsPartitionTheCoefficients) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int64_t> u(-1000, 100000);
  std::vector<IntVec3> points(5000);
  for (auto& p : points) p = {u(rng), u(rng), u(rng)};
  points[17] = points[18] = points[19];  // coincident: an unsplittable leaf
  for (uint32_t leaf : {1u, 2u, 4u}) {
    CoefficientOctree tree(points, leaf);
    std::vector<int> seen(points.size(), 0);
    ExpectPartition(tree, tree.Root(), seen);
    for (int s : seen) EXPECT_EQ(s, 1);
  }
}

void ExpectMortonThenIndexOrder(size_t n) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int64_t> u(0, n < 1000 ? 7 : 63);  // duplicates either way
  std::vector<IntVec3> points(n);
  for (auto& p : points) p = {u(rng), u(rng), u(rng)};
  const CoefficientOctree tree(points, 4);
  auto less = [&](uint32_t a, uint32_t b) {
    // Morton order: the most significant bit where two coordinates differ,
    // over all axes, decides (ties to the earlier axis at equal bit).
    int best_bit = -1, best_axis = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const uint64_t diff = static_cast<uint64_t>(points[a][axis] ^ points[b][axis]);
      if (diff == 0) continue;
      const int bit = 63 - std::countl_zero(diff);
      if (bit > best_bit) best_bit = bit, best_axis = axis;
    }
    if (best_bit < 0) return a < b;
    return points[a][best_axis] < points[b][best_axis];
  };
  ASSERT_EQ(tree.size(), points.size());
  for (uint32_t i = 1; i < tree.size(); ++i) {
    ASSERT_TRUE(less(tree.At(i - 1), tree.At(i))) << "at " << i;
  }
}

// The order is canonical (encoder and decoder must agree bit for bit): by
// the Morton interleave of the coordinates, x the most significant of each
// bit triple, then by index among coincident positions. Checked against a
// comparison written from that definition, on points with many duplicates;
// sizes on both sides of the switch from a comparison sort to the radix sort
// (512 codes), and a single point.
TEST(CoefficientOctreeTest, OrderIsMortonCodeThenIndex) {
  for (size_t n : {1u, 7u, 200u, 511u, 512u, 20000u}) {
    SCOPED_TRACE(n);
    ExpectMortonThenIndexOrder(n);
  }
}

TEST(CoefficientOctreeTest, ChildrenAreSpatiallySeparated) {
  // Two clusters far apart end up in different children of the root.
  std::vector<IntVec3> points;
  for (int i = 0; i < 10; ++i) points.push_back({i, 0, 0});
  for (int i = 0; i < 10; ++i) points.push_back({1000 + i, 1000, 1000});
  CoefficientOctree tree(points, 1);
  std::array<OctreeNode, 8> children;
  ASSERT_EQ(tree.Children(tree.Root(), children), 2);
  std::set<uint32_t> first;
  for (uint32_t i = children[0].begin; i < children[0].end; ++i) first.insert(tree.At(i));
  EXPECT_EQ(first, (std::set<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
}

TEST(ReferencePositionsTest, AreExactIntegerMidpoints) {
  const TriMesh ico = testing::Icosahedron();
  auto h = SemiRegularHierarchy::Build(12, ico.faces, 3);
  ASSERT_TRUE(h.ok());
  std::vector<IntVec3> base;
  for (const Vec3& p : ico.positions) {
    base.push_back({std::llround(p.x() * 1000), std::llround(p.y() * 1000),
                    std::llround(p.z() * 1000)});
  }
  const auto ref = ReferencePositions(**h, base);
  ASSERT_EQ(ref.size(), 3u);
  // Level 0 coefficient k sits at the sum of its edge's endpoints (scale 2).
  for (size_t k = 0; k < ref[0].size(); ++k) {
    const Edge& e = (*h)->edges(0)[k];
    for (int a = 0; a < 3; ++a) EXPECT_EQ(ref[0][k][a], base[e[0]][a] + base[e[1]][a]);
  }
  EXPECT_EQ(ref[2].size(), (*h)->subband_size(2));
}

}  // namespace
}  // namespace meshwave
