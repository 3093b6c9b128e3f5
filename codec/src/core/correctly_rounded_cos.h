// CorrectlyRoundedCos: cos(x) rounded to the nearest double, for the
// transform's weights (Zorin's butterfly rule, wavelet/prediction_stencils).
// std::cos is not: glibc and musl (WebAssembly) differ by an ulp on 4 % of
// those angles, and glibc itself differs from the rounded value from
// valence 52 on. A weight off by an ulp moves decoded positions by ulps, so
// the native and WebAssembly decoders must compute them alike: in
// double-double arithmetic (Dekker, "A floating-point technique for
// extending the available precision", 1971), Cody-Waite reduction by a
// three-part pi/2 (Cody and Waite, "Software Manual for the Elementary
// Functions", 1980) and Taylor series, then one rounding. For valences up
// to 51 the result is glibc's std::cos, so native streams stay as they
// were.
#ifndef MESHWAVE_CORE_CORRECTLY_ROUNDED_COS_H_
#define MESHWAVE_CORE_CORRECTLY_ROUNDED_COS_H_

#include <cmath>

namespace meshwave {
namespace cr_cos_internal {

struct DoubleDouble {
  double hi = 0, lo = 0;
};

// a + b exactly as hi + lo (Knuth's TwoSum).
inline DoubleDouble TwoSum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
// a * b exactly as hi + lo (fma is correctly rounded everywhere).
inline DoubleDouble TwoProd(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
inline DoubleDouble Add(DoubleDouble a, DoubleDouble b) {
  DoubleDouble s = TwoSum(a.hi, b.hi);
  s.lo += a.lo + b.lo;
  return TwoSum(s.hi, s.lo);
}
inline DoubleDouble Mul(DoubleDouble a, DoubleDouble b) {
  DoubleDouble p = TwoProd(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return TwoSum(p.hi, p.lo);
}
// a / d for a small integer d.
inline DoubleDouble Div(DoubleDouble a, double d) {
  const double q1 = a.hi / d;
  const double rem = std::fma(-q1, d, a.hi) + a.lo;  // exact remainder, plus lo
  return TwoSum(q1, rem / d);
}

// sum over i >= 0 of (-1)^i r^(2i + first) / (2i + first)!, first 0 (cos)
// or 1 (sin), for |r| <= pi/4: 20 terms reach 2^-120.
inline DoubleDouble Series(DoubleDouble r, int first) {
  const DoubleDouble r2 = Mul(r, r);
  DoubleDouble term = first == 0 ? DoubleDouble{1, 0} : r;
  DoubleDouble sum = term;
  for (int n = first; n < first + 40; n += 2) {
    term = Div(Mul(term, r2), static_cast<double>((n + 1) * (n + 2)));
    term = {-term.hi, -term.lo};
    sum = Add(sum, term);
  }
  return sum;
}

}  // namespace cr_cos_internal

// For 0 <= x <= 64 (the transform asks for angles in [0, 4 pi)).
inline double CorrectlyRoundedCos(double x) {
  using namespace cr_cos_internal;
  // pi/2 = kP1 + kP2 + kP3 to 160 bits.
  constexpr double kP1 = 0x1.921fb54442d18p+0;
  constexpr double kP2 = 0x1.1a62633145c07p-54;
  constexpr double kP3 = -0x1.f1976b7ed8fbcp-110;
  const double q = std::nearbyint(x / kP1);
  // r = x - q pi/2: x - q kP1 cancels exactly near a multiple, the rest is
  // carried in double-double.
  const DoubleDouble a = TwoProd(q, kP1);
  DoubleDouble r = TwoSum(x, -a.hi);
  r = Add(r, {-a.lo, 0});
  r = Add(r, TwoProd(-q, kP2));
  r = Add(r, {-q * kP3, 0});
  DoubleDouble v;
  switch (static_cast<long>(q) & 3) {
    case 0: v = Series(r, 0); break;
    case 1: v = Series(r, 1); v = {-v.hi, -v.lo}; break;
    case 2: v = Series(r, 0); v = {-v.hi, -v.lo}; break;
    default: v = Series(r, 1); break;
  }
  return v.hi + v.lo;
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_CORRECTLY_ROUNDED_COS_H_
