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
  // Morton position i -> the Morton positions of its same-subband
  // neighbours, kNeighbours per position: the other edges of the (one or
  // two) faces beside coefficient tree.At(i)'s edge, i itself where there
  // are fewer (a coefficient is insignificant while its own significance is
  // coded, so it counts as no neighbour).
  static constexpr int kNeighbours = 4;
  std::vector<uint32_t> neighbour_position;
};

// `values` (indexed by coefficient) rearranged into `tree`'s Morton order.
template <class T>
std::vector<T> InMortonOrder(const CoefficientOctree& tree, std::span<const T> values) {
  std::vector<T> out(tree.size());
  for (uint32_t i = 0; i < out.size(); ++i) out[i] = values[tree.At(i)];
  return out;
}

// Builds the subbands' layouts one at a time, coarsest first (subband j's
// parents are in j - 1's octree), so that a decoder can decode the coarse
// subbands' packets while the finer octrees are still being built. Each
// Next() costs about what subband j alone costs; the positions carried
// between calls are level j's vertices (ReferencePositions, level by level).
class SubbandLayoutBuilder {
 public:
  SubbandLayoutBuilder(const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid,
                       uint32_t leaf_size)
      : h_(&h), vertices_(base_grid.begin(), base_grid.end()), leaf_size_(leaf_size) {}

  // Subbands built so far.
  int built() const { return next_; }
  // The layout of subband built(); at most levels() calls.
  SubbandLayout Next() {
    const int j = next_++;
    const auto& edges = h_->edges(j);
    // Exact integer midpoints of level j's edges, at scale 2^(j+1): the
    // same positions as ReferencePositions(h, base)[j].
    std::vector<IntVec3> positions(edges.size());
    for (size_t k = 0; k < edges.size(); ++k) {
      for (int a = 0; a < 3; ++a) {
        positions[k][a] = vertices_[edges[k][0]][a] + vertices_[edges[k][1]][a];
      }
    }
    SubbandLayout layout{CoefficientOctree(positions, leaf_size_), {}, {}};
    std::vector<uint32_t> position_of(layout.tree.size());
    for (uint32_t i = 0; i < position_of.size(); ++i) position_of[layout.tree.At(i)] = i;
    layout.neighbour_position.resize(size_t{SubbandLayout::kNeighbours} * layout.tree.size());
    const auto& edge_faces = h_->edge_faces(j);
    const auto& face_edges = h_->face_edges(j);
    for (uint32_t i = 0; i < layout.tree.size(); ++i) {
      const uint32_t k = layout.tree.At(i);
      uint32_t* out = &layout.neighbour_position[size_t{SubbandLayout::kNeighbours} * i];
      int n = 0;
      for (uint32_t f : edge_faces[k]) {
        if (f == SemiRegularHierarchy::kNone) continue;
        for (uint32_t e : face_edges[f]) {
          if (e != k && n < SubbandLayout::kNeighbours) out[n++] = position_of[e];
        }
      }
      for (; n < SubbandLayout::kNeighbours; ++n) out[n] = i;
    }
    if (j > 0) {
      layout.parent_position.resize(h_->subband_size(j));
      for (uint32_t i = 0; i < layout.parent_position.size(); ++i) {
        layout.parent_position[i] = position_of_[h_->Parent(j, layout.tree.At(i))];
      }
    }
    if (next_ < h_->levels()) {
      position_of_ = std::move(position_of);
      // Level j + 1's vertices: level j's at twice the scale, then the midpoints.
      for (IntVec3& v : vertices_) {
        for (int64_t& x : v) x *= 2;
      }
      vertices_.insert(vertices_.end(), positions.begin(), positions.end());
    }
    return layout;
  }

 private:
  const SemiRegularHierarchy* h_;
  std::vector<IntVec3> vertices_;      // level next_'s vertices, scale 2^next_
  std::vector<uint32_t> position_of_;  // coefficient -> Morton position, next_ - 1
  uint32_t leaf_size_;
  int next_ = 0;
};

inline std::vector<SubbandLayout> BuildSubbandLayouts(
    const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid,
    uint32_t leaf_size) {
  SubbandLayoutBuilder builder(h, base_grid, leaf_size);
  std::vector<SubbandLayout> out;
  out.reserve(h.levels());
  while (builder.built() < h.levels()) out.push_back(builder.Next());
  return out;
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
