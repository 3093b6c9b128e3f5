// Embedded deadzone scalar quantisation (Taubman & Marcellin 2002;
// the EDSQ family of Satti et al. 2011).
// With Q0 = max(0, floor(|X| / step + xi0)), the coarser quantisers of the
// family are its bitplane truncations q_n = Q0 >> n, so bitplane coding of Q0
// and a sign realises every EDSQ of the family at once.
#ifndef MESHWAVE_QUANT_DEADZONE_QUANTIZER_H_
#define MESHWAVE_QUANT_DEADZONE_QUANTIZER_H_

#include <cmath>
#include <cstdint>

namespace meshwave {

// Deadzone parameter xi0 by its 2-bit code: z = 2(1 - xi0) is the ratio of
// the deadzone to the step at the finest level.
//   0: xi0 = 0     SAQ (z = 2), the default
//   1: xi0 = 1/2   UEQ (z = 1, plain rounding)
//   2: xi0 = 1/4   z = 1.5
//   3: xi0 = -1/4  z = 2.5
inline double DeadzoneXi(int code) {
  static constexpr double kXi[4] = {0.0, 0.5, 0.25, -0.25};
  return kXi[code & 3];
}

// Largest magnitude index we code: 2^30 (bitplanes 0..30) keeps every sum
// below 2^31 and bounds the number of packets of a subband.
inline constexpr uint32_t kMaxMagnitude = (1u << 30) - 1;
inline constexpr int kMaxBitplane = 29;

// Q0 for value x: the finest-level magnitude index (clamped to the cap).
inline uint32_t QuantizeMagnitude(double x, double step, double xi0) {
  const double q = std::floor(std::fabs(x) / step + xi0);
  if (!(q > 0)) return 0;
  if (q >= kMaxMagnitude) return kMaxMagnitude;
  return static_cast<uint32_t>(q);
}

// Reconstruction of a coefficient of which the bitplanes >= n are known:
// q = Q0 >> n. Zero when q = 0, else (q + gamma - xi_n) * 2^n * step with
// xi_n = xi0 / 2^n: gamma = 1/2 is the cell midpoint.
inline double Dequantize(uint32_t q, int n, bool negative, double step,
                         double xi0, double gamma = 0.5) {
  if (q == 0) return 0.0;
  const double scale = std::ldexp(step, n);
  const double v = (static_cast<double>(q) + gamma - std::ldexp(xi0, -n)) * scale;
  return negative ? -v : v;
}

// floor(log2(q)) for q > 0; -1 for q == 0.
inline int TopBitplane(uint32_t q) {
  return q == 0 ? -1 : 31 - __builtin_clz(q);
}

}  // namespace meshwave

#endif  // MESHWAVE_QUANT_DEADZONE_QUANTIZER_H_
