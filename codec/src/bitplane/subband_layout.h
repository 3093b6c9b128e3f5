// What both sides derive per subband before coding: the octree over the
// coefficients' reference positions and each coefficient's parent.
//
// The bitplane coder keeps its state in Morton order (the octree's order),
// not in coefficient order: the passes walk the octree, so state indexed by
// Morton position is read and written sequentially, where indexing by
// coefficient scattered every access over the subband (on igea, the random
// loads and stores were a third of the decoder's time).
#ifndef MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
#define MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_

#include <memory>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"

namespace meshwave {

struct SubbandLayout {
  CoefficientOctree tree;
  // Morton position i -> the Morton position, in subband j - 1's octree, of
  // the parent of coefficient tree.At(i). Empty for d^0.
  std::vector<uint32_t> parent_position;
};

// `values` (indexed by coefficient) rearranged into `tree`'s Morton order.
template <class T>
std::vector<T> InMortonOrder(const CoefficientOctree& tree, std::span<const T> values) {
  std::vector<T> out(tree.size());
  for (uint32_t i = 0; i < out.size(); ++i) out[i] = values[tree.At(i)];
  return out;
}

inline std::vector<SubbandLayout> BuildSubbandLayouts(
    const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid,
    uint32_t leaf_size) {
  const auto positions = ReferencePositions(h, base_grid);
  std::vector<SubbandLayout> out;
  out.reserve(h.levels());
  std::vector<uint32_t> position_of;  // coefficient -> Morton position, j - 1
  for (int j = 0; j < h.levels(); ++j) {
    SubbandLayout layout{CoefficientOctree(positions[j], leaf_size), {}};
    if (j > 0) {
      layout.parent_position.resize(h.subband_size(j));
      for (uint32_t i = 0; i < layout.parent_position.size(); ++i) {
        layout.parent_position[i] = position_of[h.Parent(j, layout.tree.At(i))];
      }
    }
    position_of.resize(layout.tree.size());
    for (uint32_t i = 0; i < position_of.size(); ++i) position_of[layout.tree.At(i)] = i;
    out.push_back(std::move(layout));
  }
  return out;
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
