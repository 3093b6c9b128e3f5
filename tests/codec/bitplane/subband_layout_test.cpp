#include "bitplane/subband_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "codec/hierarchy_on_grid_testonly.h"
#include "codec/test_meshes.h"
#include "stream/precinct_partition.h"

namespace meshwave {
namespace {

// A three-level hierarchy over the icosahedron with scattered integer base
// positions, so the octrees' Morton orders differ from coefficient order.
using LayoutFixture = testing::HierarchyOnGrid;

LayoutFixture MakeLayoutFixture() {
  return testing::BuildHierarchyOnGrid(testing::Icosahedron(), 3, Vec3::Constant(1000));
}

TEST(SubbandLayoutTest, ParentPositionNamesTheParentInTheParentsMortonOrder) {
  const LayoutFixture f = MakeLayoutFixture();
  const auto layouts = BuildSubbandLayouts(*f.h, f.grid, 4);
  ASSERT_EQ(layouts.size(), 3u);
  for (const auto& subband : layouts) ASSERT_EQ(subband.size(), 1u);  // no precincts
  EXPECT_TRUE(layouts[0][0].parent_position.empty());
  int reordered = 0;
  for (int j = 1; j < 3; ++j) {
    const auto& layout = layouts[j][0];
    const auto& parent_tree = layouts[j - 1][0].tree;
    ASSERT_EQ(layout.parent_position.size(), f.h->subband_size(j));
    for (uint32_t i = 0; i < layout.parent_position.size(); ++i) {
      const uint32_t pos = layout.parent_position[i];
      ASSERT_LT(pos, parent_tree.size());
      EXPECT_EQ(parent_tree.At(pos), f.h->Parent(j, layout.tree.At(i))) << "j " << j << " i " << i;
      EXPECT_EQ(layout.coefficient[i], layout.tree.At(i));
      reordered += layout.tree.At(i) != i;
    }
  }
  // Otherwise the test could not tell positions from coefficients.
  EXPECT_GT(reordered, 0);
}

// The builder's octrees, level by level, are those of the reference
// positions computed all at once (ReferencePositions, which the octree
// tests check against their definition).
TEST(SubbandLayoutTest, TheBuilderOrdersEachLevelAsItsReferencePositions) {
  const LayoutFixture f = MakeLayoutFixture();
  const auto positions = ReferencePositions(*f.h, f.grid);
  SubbandLayoutBuilder builder(*f.h, f.grid, 4);
  for (int j = 0; j < 3; ++j) {
    ASSERT_EQ(builder.built(), j);
    const std::vector<SubbandLayout> precincts = builder.Next();
    ASSERT_EQ(precincts.size(), 1u);
    const SubbandLayout& layout = precincts[0];
    const CoefficientOctree direct(positions[j], 4);
    ASSERT_EQ(layout.tree.size(), direct.size());
    for (uint32_t i = 0; i < direct.size(); ++i) {
      ASSERT_EQ(layout.tree.At(i), direct.At(i)) << "level " << j << " position " << i;
    }
  }
  EXPECT_EQ(builder.built(), 3);
}

TEST(SubbandLayoutTest, InMortonOrderPermutesByTheTree) {
  const LayoutFixture f = MakeLayoutFixture();
  const auto layouts = BuildSubbandLayouts(*f.h, f.grid, 4);
  const CoefficientOctree& tree = layouts[2][0].tree;
  std::vector<uint32_t> values(tree.size());
  std::mt19937 rng(5);
  for (auto& v : values) v = rng() | 1;
  const std::vector<uint32_t> ordered = InMortonOrder<uint32_t>(layouts[2][0], values);
  // One zero behind: what an out-of-precinct parent position reads.
  ASSERT_EQ(ordered.size(), values.size() + 1);
  EXPECT_EQ(ordered.back(), 0u);
  for (uint32_t i = 0; i < values.size(); ++i) EXPECT_EQ(ordered[i], values[tree.At(i)]);
}

// Neighbours (3xC's nctx, docs/FORMAT.md 5.3): the other two edges of each
// face beside a coefficient's edge, as Morton positions of the same
// subband, the position itself filling the slots of a missing face. On an
// open patch, so that boundary edges (one face) are covered too.
TEST(SubbandLayoutTest, NeighboursAreTheOtherEdgesOfTheFacesBesideEachEdge) {
  const testing::HierarchyOnGrid patch =
      testing::BuildHierarchyOnGrid(testing::OpenPatch(), 3, Vec3(997, 1009, 1013));
  ASSERT_TRUE(patch.h);
  const SemiRegularHierarchy& h = *patch.h;
  const auto layouts = BuildSubbandLayouts(h, patch.grid, 4);
  int boundary = 0, interior = 0;
  for (int j = 0; j < h.levels(); ++j) {
    const SubbandLayout& layout = layouts[j][0];
    const uint32_t n = static_cast<uint32_t>(layout.tree.size());
    ASSERT_EQ(layout.neighbour_position.size(), size_t{SubbandLayout::kNeighbours} * n);
    std::vector<uint32_t> position_of(n);
    for (uint32_t i = 0; i < n; ++i) position_of[layout.tree.At(i)] = i;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t k = layout.tree.At(i);
      // Expected, from the definition.
      std::multiset<uint32_t> want;
      int faces = 0;
      for (uint32_t f = 0; f < h.faces(j).size(); ++f) {
        const auto& fe = h.face_edges(j)[f];
        if (std::find(fe.begin(), fe.end(), k) == fe.end()) continue;
        ++faces;
        for (uint32_t e : fe) {
          if (e != k) want.insert(position_of[e]);
        }
      }
      ASSERT_GE(faces, 1);
      (faces == 1 ? boundary : interior) += 1;
      std::multiset<uint32_t> got;
      int self = 0;
      for (int s = 0; s < SubbandLayout::kNeighbours; ++s) {
        const uint32_t nb = layout.neighbour_position[SubbandLayout::kNeighbours * i + s];
        ASSERT_LT(nb, n);
        if (nb == i) {
          ++self;
        } else {
          got.insert(nb);
        }
      }
      EXPECT_EQ(got, want) << "level " << j << " position " << i;
      EXPECT_EQ(self, SubbandLayout::kNeighbours - 2 * faces) << "level " << j << " position " << i;
    }
  }
  EXPECT_GT(boundary, 0);
  EXPECT_GT(interior, 0);
}

// With precincts, each precinct is a subband of its own: its positions
// name each of its coefficients once, its neighbours are its own, and a
// parent outside the parent precinct reads the zero behind that
// precinct's positions.
TEST(SubbandLayoutTest, PrecinctsHoldTheirCoefficientsAndReadOnlyTheirOwn) {
  const testing::HierarchyOnGrid torus =
      testing::BuildHierarchyOnGrid(testing::Torus(24, 16), 3, Vec3::Constant(4096));
  const SemiRegularHierarchy& h = *torus.h;
  const PrecinctPartition partition = PartitionIntoPrecincts(h, torus.grid, 400);
  const auto layouts = BuildSubbandLayouts(h, torus.grid, 8, partition.FacePrecinctsPerSubband(),
                                           partition.ParentsPerSubband());
  int outside_parents = 0, inside_parents = 0, cut_neighbours = 0;
  for (int j = 0; j < h.levels(); ++j) {
    ASSERT_EQ(layouts[j].size(), partition.count(j));
    const std::vector<uint32_t> precinct_of = CoefficientPrecincts(h, partition, j);
    std::vector<int> seen(h.subband_size(j), 0);
    std::vector<uint32_t> position_of(h.subband_size(j));
    for (uint32_t p = 0; p < layouts[j].size(); ++p) {
      const SubbandLayout& layout = layouts[j][p];
      for (uint32_t i = 0; i < layout.size(); ++i) {
        const uint32_t k = layout.coefficient[i];
        ++seen[k];
        EXPECT_EQ(precinct_of[k], p);
        position_of[k] = i;
      }
    }
    for (int n : seen) ASSERT_EQ(n, 1);
    for (uint32_t p = 0; p < layouts[j].size(); ++p) {
      const SubbandLayout& layout = layouts[j][p];
      for (uint32_t i = 0; i < layout.size(); ++i) {
        const uint32_t k = layout.coefficient[i];
        // Neighbours: the same-precinct ones among the edges of k's faces.
        std::multiset<uint32_t> want;
        for (uint32_t f : h.edge_faces(j)[k]) {
          if (f == SemiRegularHierarchy::kNone) continue;
          for (uint32_t e : h.face_edges(j)[f]) {
            if (e == k) continue;
            if (precinct_of[e] == p) {
              want.insert(position_of[e]);
            } else {
              ++cut_neighbours;
            }
          }
        }
        std::multiset<uint32_t> got;
        for (int s = 0; s < SubbandLayout::kNeighbours; ++s) {
          const uint32_t nb = layout.neighbour_position[SubbandLayout::kNeighbours * i + s];
          ASSERT_LT(nb, layout.size());
          if (nb != i) got.insert(nb);
        }
        EXPECT_EQ(got, want);
      }
      if (j == 0) continue;
      EXPECT_EQ(layout.parent_precinct, partition.Parent(j, p));
      const SubbandLayout& up = layouts[j - 1][layout.parent_precinct];
      for (uint32_t i = 0; i < layout.size(); ++i) {
        const uint32_t parent = h.Parent(j, layout.coefficient[i]);
        const uint32_t pos = layout.parent_position[i];
        if (pos == up.size()) {
          ++outside_parents;
          EXPECT_NE(CoefficientPrecincts(h, partition, j - 1)[parent], layout.parent_precinct);
        } else {
          ++inside_parents;
          ASSERT_LT(pos, up.size());
          EXPECT_EQ(up.coefficient[pos], parent);
        }
      }
    }
  }
  // Borders exist, and are the exception.
  EXPECT_GT(outside_parents, 0);
  EXPECT_GT(inside_parents, 20 * outside_parents);
  EXPECT_GT(cut_neighbours, 0);
}

}  // namespace
}  // namespace meshwave
