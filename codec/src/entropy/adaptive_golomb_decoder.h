// The decoder of the adaptive Exp-Golomb codes (entropy/adaptive_golomb.h).
#ifndef MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_DECODER_H_
#define MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_DECODER_H_

#include <cstdint>

#include "entropy/adaptive_golomb.h"
#include "entropy/arithmetic_decoder.h"

namespace meshwave {

// Never loops more than kMaxClass times, whatever the bytes.
inline uint32_t DecodeGolomb(ArithmeticDecoder& dec, GolombContexts& ctx) {
  int k = 0;
  while (k < GolombContexts::kMaxClass && dec.Decode(ctx.unary[k])) ++k;
  const uint64_t low = k > 0 ? dec.DecodeBits(k) : 0;
  const uint64_t v = (uint64_t{1} << k) + low - 1;
  return v > 0xffffffffull ? 0xffffffffu : static_cast<uint32_t>(v);
}

inline int64_t DecodeSignedGolomb(ArithmeticDecoder& dec, SignedGolombContexts& ctx) {
  if (dec.Decode(ctx.zero)) return 0;
  const bool negative = dec.Decode(ctx.sign);
  const int64_t m = int64_t{DecodeGolomb(dec, ctx.magnitude)} + 1;
  return negative ? -m : m;
}

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_DECODER_H_
