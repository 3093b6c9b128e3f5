// What both sides derive per subband before coding: per precinct, the
// octree over its coefficients' reference positions, each coefficient's
// parent and neighbours.
//
// The bitplane coder keeps its state in Morton order (the octree's order),
// not in coefficient order: the passes walk the octree, so state indexed by
// Morton position is read and written sequentially, where indexing by
// coefficient scattered every access over the subband (on igea, the random
// loads and stores were a third of the decoder's time).
#ifndef MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
#define MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"
#include "semiregular/base_face_of.h"

namespace meshwave {

// The layout of one precinct of a subband (stream/precinct_partition.h):
// the whole subband in a stream without precincts. A precinct is coded as
// a subband of its own: its octree spans its coefficients only, and its
// contexts read only what lies in it, so that its packets decode in any
// order relative to the other precincts'.
struct SubbandLayout {
  CoefficientOctree tree;
  // Morton position i -> the coefficient of the subband (an index into
  // d^j) it holds.
  std::vector<uint32_t> coefficient;
  // Morton position i -> the Morton position, in precinct parent_precinct
  // of subband j - 1, of the parent of coefficient[i]; that precinct's size
  // (a position whose magnitude stays zero: ComponentState keeps one) when
  // the parent lies in another precinct. Empty for d^0.
  std::vector<uint32_t> parent_position;
  uint32_t parent_precinct = 0;
  // Morton position i -> the Morton positions of its same-subband,
  // same-precinct neighbours, kNeighbours per position: the other edges of
  // the (one or two) faces beside coefficient[i]'s edge, i itself where
  // there are fewer (a coefficient is insignificant while its own
  // significance is coded, so it counts as no neighbour).
  static constexpr int kNeighbours = 4;
  std::vector<uint32_t> neighbour_position;

  size_t size() const { return coefficient.size(); }
};

// `values` (indexed by the subband's coefficients) rearranged into the
// precinct's Morton order, with one zero behind for the out-of-precinct
// parent position.
template <class T>
std::vector<T> InMortonOrder(const SubbandLayout& layout, std::span<const T> values) {
  std::vector<T> out(layout.size() + 1, T{});
  for (uint32_t i = 0; i < layout.size(); ++i) out[i] = values[layout.coefficient[i]];
  return out;
}

// Builds the subbands' layouts one at a time, coarsest first (subband j's
// parents are in j - 1's octrees), so that a decoder can decode the coarse
// subbands' packets while the finer octrees are still being built. Each
// Next() costs about what subband j alone costs; the positions carried
// between calls are level j's vertices (ReferencePositions, level by level).
class SubbandLayoutBuilder {
 public:
  // `precinct_of_face[j][f]`: the precinct of base face f in subband j
  // (PrecinctPartition::FacePrecincts), with `parent_of[j][p]` the precinct
  // of subband j - 1 that precinct p lies in; empty: one precinct per
  // subband.
  SubbandLayoutBuilder(const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid,
                       uint32_t leaf_size,
                       std::vector<std::vector<uint32_t>> precinct_of_face = {},
                       std::vector<std::vector<uint32_t>> parent_of = {})
      : h_(&h),
        vertices_(base_grid.begin(), base_grid.end()),
        leaf_size_(leaf_size),
        precinct_of_face_(std::move(precinct_of_face)),
        parent_of_(std::move(parent_of)) {}

  // Subbands built so far.
  int built() const { return next_; }
  // The layouts of the precincts of subband built(); at most levels() calls.
  std::vector<SubbandLayout> Next() {
    const int j = next_++;
    const auto& edges = h_->edges(j);
    const uint32_t n = static_cast<uint32_t>(edges.size());
    // Exact integer midpoints of level j's edges, at scale 2^(j+1): the
    // same positions as ReferencePositions(h, base)[j].
    std::vector<IntVec3> positions(n);
    for (size_t k = 0; k < n; ++k) {
      for (int a = 0; a < 3; ++a) {
        positions[k][a] = vertices_[edges[k][0]][a] + vertices_[edges[k][1]][a];
      }
    }
    // Each coefficient's precinct, and the precincts' members in
    // coefficient order.
    std::vector<uint32_t> precinct_of(n, 0);
    uint32_t count = 1;
    if (!precinct_of_face_.empty()) {
      const auto& of_face = precinct_of_face_[static_cast<size_t>(j)];
      for (uint32_t k = 0; k < n; ++k) {
        precinct_of[k] = of_face[BaseFaceOf(*h_, j, k)];
        count = std::max(count, precinct_of[k] + 1);
      }
    }
    std::vector<SubbandLayout> out;
    out.reserve(count);
    std::vector<uint32_t> position_of(n);  // coefficient -> position in its precinct
    std::vector<std::vector<uint32_t>> members(count > 1 ? count : 0);
    for (uint32_t k = 0; k < n && count > 1; ++k) members[precinct_of[k]].push_back(k);
    for (uint32_t p = 0; p < count; ++p) {
      // One precinct: the whole subband, no copies.
      std::vector<IntVec3> own;
      if (count > 1) {
        own.reserve(members[p].size());
        for (uint32_t k : members[p]) own.push_back(positions[k]);
      }
      SubbandLayout layout{CoefficientOctree(count > 1 ? own : positions, leaf_size_), {}, {}, 0, {}};
      layout.coefficient.resize(layout.tree.size());
      for (uint32_t i = 0; i < layout.coefficient.size(); ++i) {
        const uint32_t local = layout.tree.At(i);
        layout.coefficient[i] = count > 1 ? members[p][local] : local;
        position_of[layout.coefficient[i]] = i;
      }
      if (j > 0 && !parent_of_.empty()) layout.parent_precinct = parent_of_[static_cast<size_t>(j)][p];
      out.push_back(std::move(layout));
    }
    const auto& edge_faces = h_->edge_faces(j);
    const auto& face_edges = h_->face_edges(j);
    for (uint32_t p = 0; p < count; ++p) {
      SubbandLayout& layout = out[p];
      layout.neighbour_position.resize(size_t{SubbandLayout::kNeighbours} * layout.size());
      for (uint32_t i = 0; i < layout.size(); ++i) {
        const uint32_t k = layout.coefficient[i];
        uint32_t* nb = &layout.neighbour_position[size_t{SubbandLayout::kNeighbours} * i];
        int m = 0;
        for (uint32_t f : edge_faces[k]) {
          if (f == SemiRegularHierarchy::kNone) continue;
          for (uint32_t e : face_edges[f]) {
            if (e != k && precinct_of[e] == p && m < SubbandLayout::kNeighbours) {
              nb[m++] = position_of[e];
            }
          }
        }
        for (; m < SubbandLayout::kNeighbours; ++m) nb[m] = i;
      }
      if (j > 0) {
        const uint32_t up = layout.parent_precinct;
        layout.parent_position.resize(layout.size());
        for (uint32_t i = 0; i < layout.size(); ++i) {
          const uint32_t parent = h_->Parent(j, layout.coefficient[i]);
          layout.parent_position[i] =
              precinct_of_[parent] == up ? position_of_[parent] : precinct_sizes_[up];
        }
      }
    }
    if (next_ < h_->levels()) {
      position_of_ = std::move(position_of);
      precinct_of_ = std::move(precinct_of);
      precinct_sizes_.resize(count);
      for (uint32_t p = 0; p < count; ++p) precinct_sizes_[p] = static_cast<uint32_t>(out[p].size());
      // Level j + 1's vertices: level j's at twice the scale, then the midpoints.
      for (IntVec3& v : vertices_) {
        for (int64_t& x : v) x *= 2;
      }
      vertices_.insert(vertices_.end(), positions.begin(), positions.end());
    }
    return out;
  }

 private:
  const SemiRegularHierarchy* h_;
  std::vector<IntVec3> vertices_;  // level next_'s vertices, scale 2^next_
  uint32_t leaf_size_;
  std::vector<std::vector<uint32_t>> precinct_of_face_;
  std::vector<std::vector<uint32_t>> parent_of_;
  // Of subband next_ - 1: each coefficient's precinct and position in it,
  // and the precincts' sizes.
  std::vector<uint32_t> position_of_;
  std::vector<uint32_t> precinct_of_;
  std::vector<uint32_t> precinct_sizes_;
  int next_ = 0;
};

// Every subband's precinct layouts, coarsest first.
inline std::vector<std::vector<SubbandLayout>> BuildSubbandLayouts(
    const SemiRegularHierarchy& h, std::span<const IntVec3> base_grid, uint32_t leaf_size,
    std::vector<std::vector<uint32_t>> precinct_of_face = {},
    std::vector<std::vector<uint32_t>> parent_of = {}) {
  SubbandLayoutBuilder builder(h, base_grid, leaf_size, std::move(precinct_of_face),
                               std::move(parent_of));
  std::vector<std::vector<SubbandLayout>> out;
  out.reserve(h.levels());
  while (builder.built() < h.levels()) out.push_back(builder.Next());
  return out;
}

}  // namespace meshwave

#endif  // MESHWAVE_BITPLANE_SUBBAND_LAYOUT_H_
