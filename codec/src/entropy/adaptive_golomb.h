// Integers as adaptive Exp-Golomb codes over the binary arithmetic coder:
// the bit-length class of (value + 1) in unary, one context per unary
// position, then the bits below the leading one as bypass bits. Used where
// values are small but unbounded (base-mesh residuals and index deltas).
// The contexts both sides keep; the codes: adaptive_golomb_encoder.h,
// adaptive_golomb_decoder.h.
#ifndef MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_
#define MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_

#include "entropy/context_model.h"

namespace meshwave {

struct GolombContexts {
  static constexpr int kMaxClass = 32;  // values below 2^32 - 1
  BinaryContext unary[kMaxClass + 1];
};

// Signed values: a zero flag (1: the value is zero), then a sign (1:
// negative) and |value| - 1.
struct SignedGolombContexts {
  BinaryContext zero;
  BinaryContext sign;
  GolombContexts magnitude;
};

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_
