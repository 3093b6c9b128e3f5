// Points sorted along a 3D Hilbert curve (docs/FORMAT.md 2.2): the order
// the precincts cut into runs. Unlike the Morton (Z) order, consecutive
// cells of a Hilbert curve always touch, so a run of it is one compact
// patch, where a Morton run can jump across the object (on a sphere, a
// run of ten base faces spanned more than a hemisphere).
//
// The index follows Skilling, "Programming the Hilbert curve" (AIP Conf.
// Proc. 707, 2004): coordinates scaled to 21 bits as the coefficient
// octree scales them (FORMAT.md 5.1), transposed to the Hilbert index's
// bits, interleaved x first.
#ifndef MESHWAVE_CORE_HILBERT_ORDER_H_
#define MESHWAVE_CORE_HILBERT_ORDER_H_

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace meshwave {

inline constexpr int kHilbertBits = 21;

// The Hilbert index of a point of [0, 2^21)^3.
inline uint64_t HilbertIndex(std::array<uint32_t, 3> x) {
  constexpr uint32_t kTop = 1u << (kHilbertBits - 1);
  // Inverse undo of the curve's rotations, from the top bit down.
  for (uint32_t q = kTop; q > 1; q >>= 1) {
    const uint32_t p = q - 1;
    for (int i = 0; i < 3; ++i) {
      if (x[static_cast<size_t>(i)] & q) {
        x[0] ^= p;  // invert the low bits of x
      } else {
        const uint32_t t = (x[0] ^ x[static_cast<size_t>(i)]) & p;  // exchange them
        x[0] ^= t;
        x[static_cast<size_t>(i)] ^= t;
      }
    }
  }
  // Gray encode.
  x[1] ^= x[0];
  x[2] ^= x[1];
  uint32_t t = 0;
  for (uint32_t q = kTop; q > 1; q >>= 1) {
    if (x[2] & q) t ^= q - 1;
  }
  for (uint32_t& v : x) v ^= t;
  uint64_t index = 0;
  for (int bit = kHilbertBits - 1; bit >= 0; --bit) {
    for (int i = 0; i < 3; ++i) index = index << 1 | ((x[static_cast<size_t>(i)] >> bit) & 1u);
  }
  return index;
}

// The indices of `points` sorted by (Hilbert index, position in `points`),
// the points first scaled to 21 bits: u = p - lo (lo the component-wise
// minimum), shifted right by s - 21 when the largest extent needs s > 21
// bits, else left by 21 - s.
inline std::vector<uint32_t> HilbertOrder(std::span<const std::array<int64_t, 3>> points) {
  std::vector<uint32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0u);
  if (points.empty()) return order;
  std::array<int64_t, 3> lo = points[0], hi = points[0];
  for (const auto& p : points) {
    for (int a = 0; a < 3; ++a) {
      lo[static_cast<size_t>(a)] = std::min(lo[static_cast<size_t>(a)], p[static_cast<size_t>(a)]);
      hi[static_cast<size_t>(a)] = std::max(hi[static_cast<size_t>(a)], p[static_cast<size_t>(a)]);
    }
  }
  uint64_t extent = 0;
  for (int a = 0; a < 3; ++a) {
    extent = std::max(extent, static_cast<uint64_t>(hi[static_cast<size_t>(a)] -
                                                     lo[static_cast<size_t>(a)]));
  }
  const int s = std::bit_width(extent);
  std::vector<uint64_t> key(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    std::array<uint32_t, 3> x{};
    for (int a = 0; a < 3; ++a) {
      const auto u = static_cast<uint64_t>(points[k][static_cast<size_t>(a)] -
                                           lo[static_cast<size_t>(a)]);
      x[static_cast<size_t>(a)] = static_cast<uint32_t>(
          s >= kHilbertBits ? u >> (s - kHilbertBits) : u << (kHilbertBits - s));
    }
    key[k] = HilbertIndex(x);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return key[a] < key[b]; });
  return order;
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_HILBERT_ORDER_H_
