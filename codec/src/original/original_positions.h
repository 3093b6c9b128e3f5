// The original layer's positions (docs/FORMAT.md 2.5): every vertex on an
// integer grid (step = the original's bounding-box diagonal x
// 2^-precision), travelling as a coarse packet (q >> shift, predicted along
// the traversal) and then `shift` refinement packets, one bit of every
// coordinate each, most significant first.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_H_

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"
#include "original/original_traversal.h"

namespace meshwave::original {

using GridPoint = std::array<uint32_t, 3>;  // each coordinate <= kMaxGridCoordinate

inline constexpr uint32_t kMaxGridCoordinate = (1u << 30) - 1;
inline constexpr int kMaxShift = 8;

// Payload 0: every vertex's q >> shift in traversal order; payload s
// (1 ... shift): bit shift - s of every coordinate of every vertex, in order.
// `q` is indexed by vertex id; `shift` in [0, kMaxShift].
std::vector<std::string> EncodePositions(const Traversal& traversal, std::span<const GridPoint> q,
                                         int shift);

class PositionsDecoder {
 public:
  // `traversal` must outlive the decoder; coordinates above
  // `max_coordinate` (the header's grid extent) are refused.
  PositionsDecoder(const Traversal& traversal, int shift, uint32_t max_coordinate);

  // Payload k (0 ... shift), in that order. Untrusted bytes: damage is a
  // kParseError, a payload out of order kInvalidArgument (nothing changed).
  Status Add(int k, std::string_view payload);
  int held() const { return held_; }

  // Per vertex id, its position in grid units: the middle of the cell the
  // bits held leave it in (q itself once every payload is held). Empty
  // before payload 0.
  std::vector<std::array<double, 3>> GridPositions() const;

 private:
  const Traversal& traversal_;
  int shift_;
  uint32_t max_coordinate_;
  int held_ = 0;
  std::vector<GridPoint> known_;  // by vertex id: the bits held, low bits zero
};

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_H_
