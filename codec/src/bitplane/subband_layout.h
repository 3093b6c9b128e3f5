// What both sides derive per subband before coding: the octree over the
// coefficients' reference positions and each coefficient's parent.
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
  std::vector<uint32_t> parent_of;  // empty for d^0
};

inline std::vector<SubbandLayout> BuildSubbandLayouts(
    const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid,
    uint32_t leaf_size) {
  const auto positions = ReferencePositions(h, base_grid);
  std::vector<SubbandLayout> out;
  out.reserve(h.levels());
  for (int j = 0; j < h.levels(); ++j) {
    SubbandLayout layout{CoefficientOctree(positions[j], leaf_size), {}};
    if (j > 0) {
      layout.parent_of.resize(h.subband_size(j));
      for (uint32_t k = 0; k < layout.parent_of.size(); ++k) {
        layout.parent_of[k] = h.Parent(j, k);
      }
    }
    out.push_back(std::move(layout));
  }
  return out;
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
