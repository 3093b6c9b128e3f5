#include <bit>
#include <cassert>
#include <string>
#include <vector>

#include "entropy/arithmetic_encoder.h"
#include "original/original_positions.h"
#include "original/original_positions_model.h"

namespace meshwave::original {
namespace {

void EncodeResidual(ArithmeticEncoder& enc, ResidualContexts& ctx, int64_t residual) {
  enc.Encode(residual == 0, ctx.zero);
  if (residual == 0) return;
  enc.Encode(residual < 0, ctx.sign);
  const uint64_t u = residual < 0 ? static_cast<uint64_t>(-residual) : static_cast<uint64_t>(residual);
  const int k = std::bit_width(u) - 1;  // u < 2^31: k <= 30
  for (int i = 0; i < k; ++i) enc.Encode(1, ctx.unary[i]);
  enc.Encode(0, ctx.unary[k]);
  if (k > 0) {
    enc.Encode((u >> (k - 1)) & 1, ctx.second_bit[k]);
    enc.EncodeBits(static_cast<uint32_t>(u & ((uint64_t{1} << (k - 1)) - 1)), k - 1);
  }
}

std::string EncodeCoarsePositions(const Traversal& traversal, std::span<const GridPoint> q,
                                  int shift) {
  const auto coarse = [&](uint32_t v, int k) { return int64_t{q[v][k] >> shift}; };
  const int64_t top = int64_t{kMaxGridCoordinate} >> shift;
  ArithmeticEncoder enc;
  CoarseContexts contexts;
  int last_class = 0;
  uint32_t previous = kNoVertex;
  for (size_t i = 0; i < traversal.order.size(); ++i) {
    const uint32_t v = traversal.order[i];
    const Prediction& p = traversal.predictions[i];
    const PredictionKind kind = KindOf(p);
    int64_t largest = 0;
    for (int k = 0; k < 3; ++k) {
      const int64_t predicted = PredictComponent(kind, p, previous, k, top, coarse);
      const int64_t residual = coarse(v, k) - predicted;
      EncodeResidual(enc, contexts.residual[static_cast<int>(kind)][k][last_class],
                         residual);
      largest = std::max(largest, std::abs(residual));
      last_class = ResidualClass(largest);
    }
    previous = v;
  }
  return enc.Finish();
}

// Bit `bit` of every coordinate, in traversal order; `known` holds the bits
// above it and takes this one.
std::string EncodeRefinementPlane(const Traversal& traversal, std::span<const GridPoint> q,
                                  int bit, std::vector<GridPoint>& known) {
  ArithmeticEncoder enc;
  RefinementContexts contexts;
  const auto at = [&](uint32_t v, int k) { return int64_t{known[v][k] >> bit}; };
  const int64_t top = int64_t{kMaxGridCoordinate} >> bit;
  uint32_t previous = kNoVertex;
  for (size_t i = 0; i < traversal.order.size(); ++i) {
    const uint32_t v = traversal.order[i];
    const Prediction& p = traversal.predictions[i];
    const PredictionKind kind = KindOf(p);
    for (int k = 0; k < 3; ++k) {
      const int cls = RefinementClass(kind, p, previous, v, k, top, at);
      const uint32_t b = (q[v][k] >> bit) & 1;
      enc.Encode(static_cast<int>(b), contexts.bit[k][cls]);
      known[v][k] |= b << bit;
    }
    previous = v;
  }
  return enc.Finish();
}

}  // namespace

std::vector<std::string> EncodePositions(const Traversal& traversal, std::span<const GridPoint> q,
                                         int shift) {
  assert(shift >= 0 && shift <= kMaxShift);
  assert(traversal.order.size() == q.size() && traversal.predictions.size() == q.size());
  std::vector<std::string> payloads;
  payloads.reserve(shift + 1);
  payloads.push_back(EncodeCoarsePositions(traversal, q, shift));
  std::vector<GridPoint> known(q.begin(), q.end());
  for (GridPoint& point : known) {
    for (uint32_t& x : point) x = (x >> shift) << shift;
  }
  for (int s = 1; s <= shift; ++s) {
    payloads.push_back(EncodeRefinementPlane(traversal, q, shift - s, known));
  }
  return payloads;
}

}  // namespace meshwave::original
