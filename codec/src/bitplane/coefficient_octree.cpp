#include "bitplane/coefficient_octree.h"

#include <algorithm>
#include <numeric>
#include <tuple>
#include <utility>

namespace meshwave {
namespace {

// Spreads the low 21 bits of x so that two zero bits separate each bit.
uint64_t Spread(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

// Sorts `codes` (with `order` alongside) by code, ties kept in their
// current order: an LSD radix sort in 11-bit digits, skipping digits that
// every code shares. With `order` starting as 0..n-1 this is the order of
// the (code, index) pairs, in linear time (a comparison sort was a tenth of
// the decoder's set-up on large meshes).
void RadixSortByCode(std::vector<uint64_t>& codes, std::vector<uint32_t>& order) {
  constexpr int kDigitBits = 11;
  constexpr size_t kBins = size_t{1} << kDigitBits;
  const size_t n = codes.size();
  // Below a few bins' worth of codes, clearing and summing 2048 bins per
  // digit costs more than the sort (the coarse subbands; a whole small
  // mesh): a comparison sort of the pairs gives the same stable order.
  if (n < kBins / 4) {
    std::vector<std::pair<uint64_t, uint32_t>> pairs(n);
    for (size_t i = 0; i < n; ++i) pairs[i] = {codes[i], order[i]};
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t i = 0; i < n; ++i) std::tie(codes[i], order[i]) = pairs[i];
    return;
  }
  std::vector<uint64_t> codes_tmp(n);
  std::vector<uint32_t> order_tmp(n);
  std::vector<uint32_t> count(kBins);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    std::fill(count.begin(), count.end(), 0u);
    for (uint64_t c : codes) ++count[(c >> shift) & (kBins - 1)];
    if (count[(codes[0] >> shift) & (kBins - 1)] == n) continue;  // one bin
    uint32_t sum = 0;
    for (uint32_t& x : count) {
      const uint32_t here = x;
      x = sum;
      sum += here;
    }
    for (size_t i = 0; i < n; ++i) {
      const uint32_t slot = count[(codes[i] >> shift) & (kBins - 1)]++;
      codes_tmp[slot] = codes[i];
      order_tmp[slot] = order[i];
    }
    codes.swap(codes_tmp);
    order.swap(order_tmp);
  }
}

}  // namespace

CoefficientOctree::CoefficientOctree(std::span<const IntVec3> positions,
                                     uint32_t leaf_size)
    : leaf_size_(std::max<uint32_t>(leaf_size, 1)) {
  const size_t n = positions.size();
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  codes_.resize(n);
  if (n == 0) return;
  IntVec3 lo = positions[0], hi = positions[0];
  for (const IntVec3& p : positions) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  int64_t extent = 0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, hi[a] - lo[a]);
  int bits = 0;
  while (bits < 62 && (int64_t{1} << bits) <= extent) ++bits;
  // The root is the power-of-two cube that encloses the positions, scaled
  // to 21 bits per axis, so the first split already separates them.
  const int shift = bits - kMaxDepth;
  for (size_t i = 0; i < n; ++i) {
    uint64_t c = 0;
    for (int a = 0; a < 3; ++a) {
      const uint64_t x = static_cast<uint64_t>(positions[i][a] - lo[a]);
      c |= Spread(shift >= 0 ? x >> shift : x << -shift) << (2 - a);
    }
    codes_[i] = c;
  }
  // Ties by index, as the canonical order requires: order_ starts 0..n-1
  // and the sort is stable.
  RadixSortByCode(codes_, order_);
}

int CoefficientOctree::Children(const OctreeNode& n,
                                std::array<OctreeNode, 8>& out) const {
  const int shift = 3 * (kMaxDepth - 1 - static_cast<int>(n.depth));
  int count = 0;
  uint32_t begin = n.begin;
  while (begin < n.end) {
    // The child holds the codes that share this code's prefix down to and
    // including the digit at this depth.
    const uint64_t low_bits = (uint64_t{1} << shift) - 1;
    const uint64_t limit = (codes_[begin] & ~low_bits) | low_bits;
    const uint32_t end = static_cast<uint32_t>(
        std::upper_bound(codes_.begin() + begin, codes_.begin() + n.end, limit) -
        codes_.begin());
    out[count++] = {begin, end, n.depth + 1};
    begin = end;
  }
  return count;
}

std::vector<std::vector<IntVec3>> ReferencePositions(
    const SemiRegularHierarchy& hierarchy, std::span<const IntVec3> base) {
  const int levels = hierarchy.levels();
  std::vector<std::vector<IntVec3>> out(levels);
  std::vector<IntVec3> current(base.begin(), base.end());
  for (int j = 0; j < levels; ++j) {
    const auto& edges = hierarchy.edges(j);
    std::vector<IntVec3>& sub = out[j];
    sub.resize(edges.size());
    for (size_t k = 0; k < edges.size(); ++k) {
      for (int a = 0; a < 3; ++a) {
        sub[k][a] = current[edges[k][0]][a] + current[edges[k][1]][a];
      }
    }
    if (j + 1 < levels) {
      for (IntVec3& p : current) {
        for (int64_t& x : p) x *= 2;
      }
      current.insert(current.end(), sub.begin(), sub.end());
    }
  }
  return out;
}

}  // namespace meshwave
