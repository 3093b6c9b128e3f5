#include <cassert>
#include <string>
#include <vector>

#include "entropy/adaptive_golomb_encoder.h"
#include "entropy/arithmetic_encoder.h"
#include "original/original_positions.h"
#include "original/original_positions_model.h"

namespace meshwave::original {
namespace {

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
    for (int k = 0; k < 3; ++k) {
      const int64_t predicted = PredictComponent(kind, p, previous, k, top, coarse);
      const int64_t residual = coarse(v, k) - predicted;
      EncodeSignedGolomb(enc, contexts.residual[static_cast<int>(kind)][k][last_class],
                         residual);
      last_class = ResidualClass(residual);
    }
    previous = v;
  }
  return enc.Finish();
}

// Bit `bit` of every coordinate, in traversal order.
std::string EncodeRefinementPlane(const Traversal& traversal, std::span<const GridPoint> q,
                                  int bit) {
  ArithmeticEncoder enc;
  RefinementContexts contexts;
  for (const uint32_t v : traversal.order) {
    for (int k = 0; k < 3; ++k) enc.Encode((q[v][k] >> bit) & 1, contexts.bit[k]);
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
  for (int s = 1; s <= shift; ++s) {
    payloads.push_back(EncodeRefinementPlane(traversal, q, shift - s));
  }
  return payloads;
}

}  // namespace meshwave::original
