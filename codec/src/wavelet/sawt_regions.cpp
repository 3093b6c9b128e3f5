#include "wavelet/sawt_regions.h"

#include <algorithm>
#include <array>

namespace meshwave {
namespace {

using Point = std::array<int64_t, 3>;

struct Cell {
  Point lo, hi;  // half-open, in units of 1/3 grid step
  int depth = 0;
};

// Depth-first over the octree; `decide(depth, faces)` is asked for every
// node that could be split and is not decided by what both sides know
// (fewer than two faces, all faces at one point, maximal depth).
class RegionTraversal {
 public:
  RegionTraversal(const SemiRegularHierarchy& h, std::span<const IntVec3> grid,
                  const std::function<bool(int, std::span<const uint32_t>)>& decide)
      : decide_(decide) {
    const auto& faces = h.faces(0);
    centroid3_.reserve(faces.size());
    result_.face_region.assign(faces.size(), 0);
    for (const Face& face : faces) {
      Point c;
      for (int a = 0; a < 3; ++a) c[a] = grid[face[0]][a] + grid[face[1]][a] + grid[face[2]][a];
      centroid3_.push_back(c);
    }
    Cell root;
    for (int a = 0; a < 3; ++a) {
      int64_t lo = 0, hi = 0;
      for (size_t v = 0; v < grid.size(); ++v) {
        lo = v == 0 ? grid[v][a] : std::min(lo, grid[v][a]);
        hi = v == 0 ? grid[v][a] : std::max(hi, grid[v][a]);
      }
      root.lo[a] = 3 * lo;
      root.hi[a] = 3 * hi + 1;
    }
    std::vector<uint32_t> all(faces.size());
    for (uint32_t f = 0; f < all.size(); ++f) all[f] = f;
    if (!all.empty()) Visit(root, all);
  }

  SawtRegions Take() { return std::move(result_); }

 private:
  bool Decidable(const Cell& cell, const std::vector<uint32_t>& faces) const {
    if (faces.size() < 2 || cell.depth >= kSawtMaxDepth) return false;
    for (uint32_t f : faces) {
      if (centroid3_[f] != centroid3_[faces[0]]) return true;
    }
    return false;
  }

  void Visit(const Cell& cell, const std::vector<uint32_t>& faces) {
    if (!Decidable(cell, faces) || !decide_(cell.depth, faces)) {
      for (uint32_t f : faces) result_.face_region[f] = result_.count;
      ++result_.count;
      return;
    }
    Point mid;
    for (int a = 0; a < 3; ++a) mid[a] = cell.lo[a] + (cell.hi[a] - cell.lo[a]) / 2;
    std::array<std::vector<uint32_t>, 8> parts;
    for (uint32_t f : faces) {
      int c = 0;
      for (int a = 0; a < 3; ++a) c |= (centroid3_[f][a] >= mid[a] ? 1 : 0) << a;
      parts[c].push_back(f);
    }
    for (int c = 0; c < 8; ++c) {
      if (parts[c].empty()) continue;
      Cell child;
      child.depth = cell.depth + 1;
      for (int a = 0; a < 3; ++a) {
        const bool upper = (c >> a) & 1;
        child.lo[a] = upper ? mid[a] : cell.lo[a];
        child.hi[a] = upper ? cell.hi[a] : mid[a];
      }
      Visit(child, parts[c]);
    }
  }

  const std::function<bool(int, std::span<const uint32_t>)>& decide_;
  std::vector<Point> centroid3_;
  SawtRegions result_;
};

}  // namespace

std::vector<uint32_t> SawtOddVertexRegions(const SemiRegularHierarchy& h, int j,
                                           const std::vector<uint32_t>& face_region) {
  std::vector<uint32_t> out(h.subband_size(j));
  for (uint32_t k = 0; k < out.size(); ++k) out[k] = face_region[BaseFaceOf(h, j, k)];
  return out;
}

SawtRegions BuildSawtRegions(const SemiRegularHierarchy& h,
                             std::span<const IntVec3> base_grid, uint32_t alpha) {
  // Odd vertices (all levels) per base face: what a cell "holds".
  std::vector<uint64_t> held(h.faces(0).size(), 0);
  for (int j = 0; j < h.levels(); ++j) AddCoefficientsPerBaseFace(h, j, held);
  std::vector<uint8_t> flags;
  const std::function<bool(int, std::span<const uint32_t>)> decide =
      [&](int, std::span<const uint32_t> faces) {
        uint64_t n = 0;
        for (uint32_t f : faces) n += held[f];
        const bool split = n >= alpha;
        flags.push_back(split ? 1 : 0);
        return split;
      };
  SawtRegions out = RegionTraversal(h, base_grid, decide).Take();
  out.split_flags = std::move(flags);
  return out;
}

SawtRegions ReplaySawtRegions(const SemiRegularHierarchy& h,
                              std::span<const IntVec3> base_grid,
                              const std::function<int(int depth)>& read_flag) {
  const std::function<bool(int, std::span<const uint32_t>)> decide =
      [&](int depth, std::span<const uint32_t>) { return read_flag(depth) != 0; };
  return RegionTraversal(h, base_grid, decide).Take();
}

}  // namespace meshwave
