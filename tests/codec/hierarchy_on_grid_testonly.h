// A semi-regular hierarchy over one of the test meshes together with its
// base vertices on an integer grid, as the coder's layouts, the SAWT
// regions and the precincts take them from the header's quantised base.
#ifndef MESHWAVE_TESTS_CODEC_HIERARCHY_ON_GRID_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_HIERARCHY_ON_GRID_TESTONLY_H_

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"

namespace meshwave::testing {

struct HierarchyOnGrid {
  std::shared_ptr<const SemiRegularHierarchy> h;
  std::vector<IntVec3> grid;  // base vertex positions scaled and rounded
};

// `levels` subdivisions of `base`; each axis scaled by its own factor, so
// that a caller can keep integer positions from tying.
inline HierarchyOnGrid BuildHierarchyOnGrid(const TriMesh& base, int levels,
                                            const Vec3& scale) {
  auto built = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                           base.faces, levels);
  EXPECT_TRUE(built.ok()) << built.status().ToString();
  HierarchyOnGrid out;
  if (!built.ok()) return out;
  out.h = *built;
  for (const Vec3& p : base.positions) {
    out.grid.push_back({std::llround(p.x() * scale.x()), std::llround(p.y() * scale.y()),
                        std::llround(p.z() * scale.z())});
  }
  return out;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_HIERARCHY_ON_GRID_TESTONLY_H_
