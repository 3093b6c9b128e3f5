// The encoder of the adaptive Exp-Golomb codes (entropy/adaptive_golomb.h).
#ifndef MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_ENCODER_H_
#define MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_ENCODER_H_

#include <cstdint>

#include "entropy/adaptive_golomb.h"
#include "entropy/arithmetic_encoder.h"

namespace meshwave {

inline void EncodeGolomb(ArithmeticEncoder& enc, GolombContexts& ctx,
                         uint32_t value) {
  const uint64_t v = uint64_t{value} + 1;
  int k = 0;
  while ((v >> (k + 1)) != 0) ++k;
  for (int i = 0; i < k; ++i) enc.Encode(1, ctx.unary[i]);
  if (k < GolombContexts::kMaxClass) enc.Encode(0, ctx.unary[k]);
  if (k > 0) enc.EncodeBits(static_cast<uint32_t>(v & ((uint64_t{1} << k) - 1)), k);
}

inline void EncodeSignedGolomb(ArithmeticEncoder& enc, SignedGolombContexts& ctx,
                               int64_t value) {
  enc.Encode(value == 0, ctx.zero);
  if (value == 0) return;
  enc.Encode(value < 0, ctx.sign);
  const uint64_t m = value < 0 ? static_cast<uint64_t>(-value) : static_cast<uint64_t>(value);
  EncodeGolomb(enc, ctx.magnitude, static_cast<uint32_t>(m - 1));
}

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_ENCODER_H_
