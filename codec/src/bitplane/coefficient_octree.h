// The octree that SIM and 3xC partition a subband with (Denis et al. 2010):
// coefficients sorted by the Morton code of an integer reference position
// that encoder and decoder derive bit-exactly from the quantised base mesh,
// so every octree cell is a contiguous range of that order.
#ifndef MESHWAVE_BITPLANE_COEFFICIENT_OCTREE_H_
#define MESHWAVE_BITPLANE_COEFFICIENT_OCTREE_H_

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "meshwave/semiregular.h"

namespace meshwave {

using IntVec3 = std::array<int64_t, 3>;

// One cell: positions [begin, end) of the subband's Morton order.
struct OctreeNode {
  uint32_t begin = 0;
  uint32_t end = 0;
  uint32_t depth = 0;
};

class CoefficientOctree {
 public:
  static constexpr int kMaxDepth = 21;  // 21 bits per axis in a 63-bit code

  // `positions`: reference position of every coefficient of the subband.
  // Leaves hold at most `leaf_size` coefficients unless they cannot be split.
  CoefficientOctree(std::span<const IntVec3> positions, uint32_t leaf_size);

  size_t size() const { return order_.size(); }
  // Coefficient index at Morton position i.
  uint32_t At(uint32_t i) const { return order_[i]; }
  OctreeNode Root() const {
    return {0, static_cast<uint32_t>(order_.size()), 0};
  }
  bool IsLeaf(const OctreeNode& n) const {
    return n.end - n.begin <= leaf_size_ || n.depth >= kMaxDepth ||
           codes_[n.begin] == codes_[n.end - 1];
  }
  // The non-empty children of an inner node in Morton order; returns how
  // many were written.
  int Children(const OctreeNode& n, std::array<OctreeNode, 8>& out) const;

 private:
  std::vector<uint32_t> order_;
  std::vector<uint64_t> codes_;  // Morton code at each position of order_
  uint32_t leaf_size_;
};

// Reference positions of the coefficients of every subband: the base
// vertices' integer coordinates, refined by exact integer midpoints
// (level-j positions are scaled by 2^j). result[j][k] is the midpoint of
// edge k of M^j at scale 2^(j+1).
std::vector<std::vector<IntVec3>> ReferencePositions(
    const SemiRegularHierarchy& hierarchy, std::span<const IntVec3> base);

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_COEFFICIENT_OCTREE_H_
