// Integers as adaptive Exp-Golomb codes over the binary arithmetic coder:
// the bit-length class of (value + 1) in unary, one context per unary
// position, then the bits below the leading one as bypass bits. Used where
// values are small but unbounded (base-mesh residuals and index deltas).
#ifndef MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_
#define MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_

#include <cstdint>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"

namespace meshwave {

struct GolombContexts {
  static constexpr int kMaxClass = 32;  // values below 2^32 - 1
  BinaryContext unary[kMaxClass + 1];
};

inline void EncodeGolomb(ArithmeticEncoder& enc, GolombContexts& ctx,
                         uint32_t value) {
  const uint64_t v = uint64_t{value} + 1;
  int k = 0;
  while ((v >> (k + 1)) != 0) ++k;
  for (int i = 0; i < k; ++i) enc.Encode(1, ctx.unary[i]);
  if (k < GolombContexts::kMaxClass) enc.Encode(0, ctx.unary[k]);
  if (k > 0) enc.EncodeBits(static_cast<uint32_t>(v & ((uint64_t{1} << k) - 1)), k);
}

// Never loops more than kMaxClass times, whatever the bytes.
inline uint32_t DecodeGolomb(ArithmeticDecoder& dec, GolombContexts& ctx) {
  int k = 0;
  while (k < GolombContexts::kMaxClass && dec.Decode(ctx.unary[k])) ++k;
  const uint64_t low = k > 0 ? dec.DecodeBits(k) : 0;
  const uint64_t v = (uint64_t{1} << k) + low - 1;
  return v > 0xffffffffull ? 0xffffffffu : static_cast<uint32_t>(v);
}

// Signed values: a zero flag, a sign, then |value| - 1.
struct SignedGolombContexts {
  BinaryContext zero;
  BinaryContext sign;
  GolombContexts magnitude;
};

inline void EncodeSignedGolomb(ArithmeticEncoder& enc, SignedGolombContexts& ctx,
                               int64_t value) {
  enc.Encode(value == 0, ctx.zero);
  if (value == 0) return;
  enc.Encode(value < 0, ctx.sign);
  const uint64_t m = value < 0 ? static_cast<uint64_t>(-value) : static_cast<uint64_t>(value);
  EncodeGolomb(enc, ctx.magnitude, static_cast<uint32_t>(m - 1));
}

inline int64_t DecodeSignedGolomb(ArithmeticDecoder& dec, SignedGolombContexts& ctx) {
  if (dec.Decode(ctx.zero)) return 0;
  const bool negative = dec.Decode(ctx.sign);
  const int64_t m = int64_t{DecodeGolomb(dec, ctx.magnitude)} + 1;
  return negative ? -m : m;
}

}  // namespace meshwave

#endif  // MESHWAVE_ENTROPY_ADAPTIVE_GOLOMB_H_
