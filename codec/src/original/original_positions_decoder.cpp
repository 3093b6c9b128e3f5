#include <algorithm>
#include <string>

#include "entropy/arithmetic_decoder.h"
#include "original/original_positions.h"
#include "original/original_positions_model.h"

namespace meshwave::original {
namespace {

// The traversal comes from decoding untrusted connectivity: every vertex it
// names is checked once here, so that the decoding loops index safely. (An
// order that is no permutation gives wrong points, never a crash.)
Status CheckTraversalBounds(const Traversal& traversal) {
  const size_t n = traversal.order.size();
  if (traversal.predictions.size() != n) {
    return InvalidArgument("original positions: " + std::to_string(traversal.predictions.size()) +
                           " predictions for " + std::to_string(n) + " vertices");
  }
  for (size_t i = 0; i < n; ++i) {
    const Prediction& p = traversal.predictions[i];
    bool ok = traversal.order[i] < n;
    switch (KindOf(p)) {
      case PredictionKind::kParallelogram: ok = ok && p.c < n; [[fallthrough]];
      case PredictionKind::kMidpoint: ok = ok && p.b < n; [[fallthrough]];
      case PredictionKind::kVertex: ok = ok && p.a < n; break;
      case PredictionKind::kPrevious: break;
    }
    if (!ok) {
      return InvalidArgument("original positions: traversal entry " + std::to_string(i) +
                             " names a vertex beyond " + std::to_string(n));
    }
  }
  return Status::Ok();
}

// Never loops more than kMaxClass times, whatever the bytes.
int64_t DecodeResidual(ArithmeticDecoder& dec, ResidualContexts& ctx) {
  if (dec.Decode(ctx.zero)) return 0;
  const bool negative = dec.DecodeUnpredictable(ctx.sign);
  int k = 0;
  while (k < ResidualContexts::kMaxClass && dec.Decode(ctx.unary[k])) ++k;
  uint64_t u = 1;
  if (k > 0) {
    u = (u << 1) | static_cast<uint64_t>(dec.Decode(ctx.second_bit[k]));
    u = (u << (k - 1)) | dec.DecodeBits(k - 1);
  }
  const int64_t m = static_cast<int64_t>(u);
  return negative ? -m : m;
}

// Damaged bytes are caught by the padding budget (FORMAT.md 4.1) at the
// latest at the end; checking every so often also stops early.
inline constexpr size_t kOverrunCheckInterval = 1024;

}  // namespace

PositionsDecoder::PositionsDecoder(const Traversal& traversal, int shift, uint32_t max_coordinate)
    : traversal_(traversal), shift_(shift), max_coordinate_(max_coordinate) {}

Status PositionsDecoder::Add(int k, std::string_view payload) {
  if (k != held_) {
    return InvalidArgument("original positions: payload " + std::to_string(k) +
                           " out of turn (next: " + std::to_string(held_) + ")");
  }
  if (shift_ < 0 || shift_ > kMaxShift || max_coordinate_ > kMaxGridCoordinate) {
    return ParseError("original positions: shift " + std::to_string(shift_) +
                      " or grid extent " + std::to_string(max_coordinate_) + " out of range");
  }
  if (k > shift_) {
    return InvalidArgument("original positions: payload " + std::to_string(k) + " beyond the " +
                           std::to_string(shift_ + 1) + " payloads");
  }
  ArithmeticDecoder dec(payload);
  const std::vector<uint32_t>& order = traversal_.order;
  if (k == 0) {
    MW_RETURN_IF_ERROR(CheckTraversalBounds(traversal_));
    known_.assign(order.size(), GridPoint{});
    const auto at = [this](uint32_t v, int c) { return int64_t{known_[v][c]}; };
    const int64_t top = int64_t{max_coordinate_} >> shift_;
    const int64_t clamp_top = int64_t{kMaxGridCoordinate} >> shift_;
    CoarseContexts contexts;
    int last_class = 0;
    uint32_t previous = kNoVertex;
    for (size_t i = 0; i < order.size(); ++i) {
      const uint32_t v = order[i];
      const Prediction& p = traversal_.predictions[i];
      const PredictionKind kind = KindOf(p);
      int64_t largest = 0;
      for (int c = 0; c < 3; ++c) {
        const int64_t predicted = PredictComponent(kind, p, previous, c, clamp_top, at);
        const int64_t residual = DecodeResidual(
            dec, contexts.residual[static_cast<int>(kind)][c][last_class]);
        const int64_t value = predicted + residual;
        if (value < 0 || value > top || dec.overrun()) {
          known_.clear();
          return ParseError("original positions: vertex " + std::to_string(v) +
                            " leaves the grid or the coded bytes end");
        }
        known_[v][c] = static_cast<uint32_t>(value);
        largest = std::max(largest, residual < 0 ? -residual : residual);
        last_class = ResidualClass(largest);
      }
      previous = v;
    }
    if (dec.overrun()) {
      known_.clear();
      return ParseError("original positions: coarse points truncated");
    }
    for (GridPoint& point : known_) {
      for (uint32_t& x : point) x <<= shift_;
    }
  } else {
    const int bit = shift_ - k;
    const uint32_t top = max_coordinate_ >> bit;
    RefinementContexts contexts;
    const auto at = [this, bit](uint32_t v, int c) { return int64_t{known_[v][c] >> bit}; };
    const int64_t clamp_top = int64_t{kMaxGridCoordinate} >> bit;
    bool damaged = false;
    uint32_t previous = kNoVertex;
    for (size_t i = 0; i < order.size() && !damaged; ++i) {
      const uint32_t v = order[i];
      const Prediction& p = traversal_.predictions[i];
      const PredictionKind kind = KindOf(p);
      for (int c = 0; c < 3; ++c) {
        const int cls = RefinementClass(kind, p, previous, v, c, clamp_top, at);
        known_[v][c] |= static_cast<uint32_t>(dec.DecodeUnpredictable(contexts.bit[c][cls]))
                        << bit;
        damaged |= (known_[v][c] >> bit) > top;
      }
      if ((i % kOverrunCheckInterval) == 0) damaged |= dec.overrun();
      previous = v;
    }
    if (damaged || dec.overrun()) {
      // The plane's bits were all zero before: clearing them restores the
      // points held.
      for (GridPoint& point : known_) {
        for (uint32_t& x : point) x &= ~(uint32_t{1} << bit);
      }
      return ParseError("original positions: refinement plane " + std::to_string(k) +
                        " damaged (a point leaves the grid or the coded bytes end)");
    }
  }
  ++held_;
  return Status::Ok();
}

std::vector<std::array<double, 3>> PositionsDecoder::GridPositions() const {
  if (held_ == 0) return {};
  const int missing = shift_ - (held_ - 1);
  const double middle = ((uint32_t{1} << missing) - 1) / 2.0;
  std::vector<std::array<double, 3>> out;
  out.reserve(known_.size());
  for (const GridPoint& p : known_) out.push_back({p[0] + middle, p[1] + middle, p[2] + middle});
  return out;
}

}  // namespace meshwave::original
