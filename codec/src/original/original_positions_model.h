// What the original layer's positions encoder and decoder agree on
// (original_positions.h, docs/FORMAT.md 2.5): how a vertex's coarse point
// is predicted, and which contexts code its residuals and refinement bits.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>

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
// computed in 64 bits and clamped to [0, top]; both sides pass
// kMaxGridCoordinate at the current precision, not the header's extent, so
// the encoder needs no extent (clamping to the true extent would save
// nothing measurable: 386 predictions beyond it in 2.7 M vertices coded).
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
// magnitude class (bit length, at most 7) of the largest residual of the
// vertex so far (for x: of the previous vertex). Against one class per kind
// and component: -2.2 % bits on payload 0 over data/meshes at precision 14.
inline constexpr int kResidualClasses = 8;

inline int ResidualClass(int64_t residual) {
  const uint64_t m = static_cast<uint64_t>(std::llabs(residual));
  return std::min(std::bit_width(m), uint64_t{7});
}

// A residual r: a zero flag (1: r = 0), a sign (1: negative), then
// u = |r| as an Exp-Golomb code (docs/FORMAT.md 4.3) whose bit below the
// leading one has a context per class: residuals fall off within a class,
// so that bit is 0 more often than not (bypass bits below it).
struct ResidualContexts {
  static constexpr int kMaxClass = 32;
  BinaryContext zero;
  BinaryContext sign;
  BinaryContext unary[kMaxClass + 1];
  BinaryContext second_bit[kMaxClass + 1];
};

struct CoarseContexts {
  ResidualContexts residual[kPredictionKinds][3][kResidualClasses];
};

// Refinement contexts (one packet per plane, fresh contexts), per component
// and by where the prediction at the plane's precision falls against the
// two values the bit chooses between (2 t and 2 t + 1, t the bits held):
// below, on 2 t, on 2 t + 1, above; vertices predicted by the previous one
// apart. Every vertex earlier in the order already has the plane's bit, so
// the prediction is finer than the coarse one. Measured at precision 16,
// shift 3 (payloads 1, 2, 3, bits per coordinate, mean over the 10 meshes
// of data/meshes): 0.980, 0.986, 0.990, against 1.008 each with one
// context per component (an adaptive context at P = 1/2 pays about 1 %
// for its noise); fandisk (CAD, flat parts) 0.86.
inline constexpr int kRefinementClasses = 5;

struct RefinementContexts {
  BinaryContext bit[3][kRefinementClasses];
};

// `at(v, k)`: the points at the plane's precision (the bit still 0 for
// `vertex` and the vertices after it).
template <typename At>
inline int RefinementClass(PredictionKind kind, const Prediction& p, uint32_t previous,
                           uint32_t vertex, int k, int64_t top, const At& at) {
  if (kind == PredictionKind::kPrevious) return 0;
  const int64_t d = PredictComponent(kind, p, previous, k, top, at) - at(vertex, k);
  return d <= -1 ? 1 : d == 0 ? 2 : d == 1 ? 3 : 4;
}

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_POSITIONS_MODEL_H_
