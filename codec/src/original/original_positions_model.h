// What the original layer's positions encoder and decoder agree on
// (original_positions.h, docs/FORMAT.md 2.5): how a vertex's coarse point
// is predicted, and which contexts code its residuals and refinement bits.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_

#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "entropy/adaptive_golomb.h"
#include "entropy/context_model.h"
#include "original/original_positions.h"
#include "original/original_traversal.h"

namespace meshwave::original {

enum class PredictionKind : uint8_t { kParallelogram, kMidpoint, kVertex, kPrevious };
inline constexpr int kPredictionKinds = 4;

// The kind a Prediction names: the vertices it lists, c only with a and b,
// b only with a (ValidPredictionShape).
inline PredictionKind KindOf(const Prediction& p) {
  if (p.c != kNoVertex) return PredictionKind::kParallelogram;
  if (p.b != kNoVertex) return PredictionKind::kMidpoint;
  if (p.a != kNoVertex) return PredictionKind::kVertex;
  return PredictionKind::kPrevious;
}

// Component k of the prediction from `at(vertex)`, the points already
// decoded at the current precision; `previous` is the vertex before in the
// order (kNoVertex for the first: the origin). The parallelogram is
// computed in 64 bits and clamped to the grid [0, top].
template <typename At>
inline int64_t PredictComponent(PredictionKind kind, const Prediction& p, uint32_t previous,
                                int k, int64_t top, const At& at) {
  switch (kind) {
    case PredictionKind::kParallelogram:
      return std::clamp(at(p.a, k) + at(p.b, k) - at(p.c, k), int64_t{0}, top);
    case PredictionKind::kMidpoint:
      return (at(p.a, k) + at(p.b, k)) >> 1;
    case PredictionKind::kVertex:
      return at(p.a, k);
    case PredictionKind::kPrevious:
      break;
  }
  return previous == kNoVertex ? 0 : at(previous, k);
}

// Residual contexts: one set per prediction kind (parallelogram residuals
// are far smaller than the previous vertex's), per component, and per
// magnitude class of the residual just coded before it (the same vertex's
// previous component; for x, the previous vertex's z).
inline constexpr int kResidualClasses = 3;

inline int ResidualClass(int64_t residual) {
  const uint64_t m = static_cast<uint64_t>(std::llabs(residual));
  return m == 0 ? 0 : m <= 3 ? 1 : 2;
}

struct CoarseContexts {
  SignedGolombContexts residual[kPredictionKinds][3][kResidualClasses];
};

// Refinement contexts, one packet per plane (fresh contexts): per component.
struct RefinementContexts {
  BinaryContext bit[3];
};

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_
