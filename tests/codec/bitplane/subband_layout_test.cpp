#include "bitplane/subband_layout.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "codec/test_meshes.h"

namespace meshwave {
namespace {

// A three-level hierarchy over the icosahedron with scattered integer base
// positions, so the octrees' Morton orders differ from coefficient order.
struct LayoutFixture {
  std::shared_ptr<const SemiRegularHierarchy> h;
  std::vector<IntVec3> grid;
};

LayoutFixture MakeLayoutFixture() {
  const TriMesh ico = testing::Icosahedron();
  auto built = SemiRegularHierarchy::Build(static_cast<uint32_t>(ico.positions.size()),
                                           ico.faces, 3);
  EXPECT_TRUE(built.ok());
  LayoutFixture f{*built, {}};
  for (const Vec3& p : ico.positions) {
    f.grid.push_back({static_cast<int64_t>(p.x() * 1000), static_cast<int64_t>(p.y() * 1000),
                      static_cast<int64_t>(p.z() * 1000)});
  }
  return f;
}

TEST(SubbandLayoutTest, ParentPositionNamesTheParentInTheParentsMortonOrder) {
  const LayoutFixture f = MakeLayoutFixture();
  const auto layouts = BuildSubbandLayouts(*f.h, f.grid, 4);
  ASSERT_EQ(layouts.size(), 3u);
  EXPECT_TRUE(layouts[0].parent_position.empty());
  int reordered = 0;
  for (int j = 1; j < 3; ++j) {
    const auto& layout = layouts[j];
    const auto& parent_tree = layouts[j - 1].tree;
    ASSERT_EQ(layout.parent_position.size(), f.h->subband_size(j));
    for (uint32_t i = 0; i < layout.parent_position.size(); ++i) {
      const uint32_t pos = layout.parent_position[i];
      ASSERT_LT(pos, parent_tree.size());
      EXPECT_EQ(parent_tree.At(pos), f.h->Parent(j, layout.tree.At(i))) << "j " << j << " i " << i;
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
    const SubbandLayout layout = builder.Next();
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
  const CoefficientOctree& tree = layouts[2].tree;
  std::vector<uint32_t> values(tree.size());
  std::mt19937 rng(5);
  for (auto& v : values) v = rng();
  const std::vector<uint32_t> ordered = InMortonOrder<uint32_t>(tree, values);
  ASSERT_EQ(ordered.size(), values.size());
  for (uint32_t i = 0; i < ordered.size(); ++i) EXPECT_EQ(ordered[i], values[tree.At(i)]);
}

}  // namespace
}  // namespace meshwave
