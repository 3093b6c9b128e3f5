#include "analysis/edsq_distortion_rate.h"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace meshwave {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Entropy(double p) { return p > 0 ? -p * std::log2(p) : 0.0; }

// Value of a piecewise-linear function through (xs, ys) at x (xs ascending).
double Interpolate(const std::vector<double>& xs, const std::vector<double>& ys,
                   double x) {
  if (xs.empty() || x < xs.front() || x > xs.back()) return kNaN;
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  if (it == xs.end()) return ys.back();
  const size_t i = static_cast<size_t>(it - xs.begin());
  if (i == 0) return ys.front();
  const double t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return ys[i - 1] + t * (ys[i] - ys[i - 1]);
}

// The curve sorted by rate, points of equal rate merged (keeping the lower
// distortion), as parallel arrays.
void SortedCurve(const std::vector<DrPoint>& curve, std::vector<double>& r,
                 std::vector<double>& d) {
  std::vector<DrPoint> c = curve;
  std::sort(c.begin(), c.end(), [](const DrPoint& a, const DrPoint& b) {
    return a.rate < b.rate || (a.rate == b.rate && a.distortion < b.distortion);
  });
  r.clear();
  d.clear();
  for (const DrPoint& p : c) {
    if (!r.empty() && p.rate <= r.back() + 1e-12) continue;
    r.push_back(p.rate);
    d.push_back(p.distortion);
  }
}

}  // namespace

EdsqLevel EdsqAt(double step0, double xi0, int n) {
  return {std::ldexp(step0, n), std::ldexp(xi0, -n)};
}

double LaplacianEdsqDistortionEq28(double lambda, const EdsqLevel& q) {
  const double d = q.delta(), s = q.step;
  const double coth = 1 / std::tanh(lambda * s / 2);
  return 2 / (lambda * lambda) +
         std::exp(-lambda * s * d) *
             ((0.25 - d * d) * s * s - (2 * d + coth) * s / lambda);
}

double LaplacianEdsqDistortion(double lambda, const EdsqLevel& q) {
  // Eq. 28 regrouped as deadzone + geometric sum over cells:
  //   lambda^2 D = 2 P(3, t) + e^{-t} J(u) / (1 - e^{-u}),
  // t = lambda delta Delta, u = lambda Delta, P the regularized incomplete
  // gamma function. Literal eq. 28 subtracts terms of size sigma^2 to get
  // D ~ Delta^2 / 12 and loses about log10(sigma^2 / D) digits (1e-5
  // relative at sigma / Delta = 8000; see LaplacianEdsqDistortionEq28).
  const double t = lambda * q.delta() * q.step, u = lambda * q.step;
  const double deadzone = 2 * boost::math::gamma_p(3.0, t);
  const double rest = std::exp(-t) * ExponentialCellError(u, u / 2) / -std::expm1(-u);
  return (deadzone + rest) / (lambda * lambda);
}

double LaplacianEdsqRate(double lambda, const EdsqLevel& q) {
  const double d = q.delta(), s = q.step;
  const double c_d = std::exp(-lambda * s * d);
  const double d_d = -std::expm1(-lambda * s * d), d_1 = -std::expm1(-lambda * s);
  // Eq. 29 in logs, term by term, so that no power under- or overflows:
  // log2(2 d_d / (d_1 c_1^(1/d_1) e^{lambda s (1-d)} d_d^(1/c_d))).
  const double log2e = 1 / std::log(2.0);
  const double inner = 1 + std::log2(d_d) - std::log2(d_1) + lambda * s / d_1 * log2e -
                       lambda * s * (1 - d) * log2e - std::log2(d_d) / c_d;
  return c_d * inner;
}

DrPoint ModelDistortionRate(const SourceModel& model, const EdsqLevel& q) {
  DrPoint out;
  const double dz = q.delta() * q.step;
  const double p0 = 2 * model.Mass(0, dz);
  out.rate = Entropy(p0);
  out.distortion = 2 * model.SquaredError(0, dz, 0);
  for (int k = 1; k <= (1 << 22); ++k) {
    const double a = (k - 1 + q.delta()) * q.step, b = a + q.step;
    // Heavy tails (a generalized Gaussian of small alpha) reach far: stop
    // only when what is left can change neither D nor R.
    if (k % 64 == 1 && a > model.Sigma() && model.Mass(a, kInfinity) < 1e-15 &&
        model.SquaredError(a, kInfinity, a) < 1e-12 * out.distortion) {
      break;
    }
    out.rate += 2 * Entropy(model.Mass(a, b));
    out.distortion += 2 * model.SquaredError(a, b, (k - 0.5 + q.delta()) * q.step);
  }
  return out;
}

DrPoint MixtureDistortionRate(const LaplacianMixture& model, const EdsqLevel& q) {
  DrPoint out;
  const double b = model.beta();
  const double l1 = model.component1().lambda(), l2 = model.component2().lambda();
  out.distortion = b * LaplacianEdsqDistortion(l1, q) +
                   (1 - b) * LaplacianEdsqDistortion(l2, q);
  // P_k = sum_m w_m e^{-l_m (k-1+delta) Delta} (1 - e^{-l_m Delta}) / 2.
  const double dz = q.delta() * q.step;
  out.rate = Entropy(model.Mass(0, dz) * 2);
  const double m1 = -std::expm1(-l1 * q.step), m2 = -std::expm1(-l2 * q.step);
  double e1 = std::exp(-l1 * dz), e2 = std::exp(-l2 * dz);
  const double r1 = std::exp(-l1 * q.step), r2 = std::exp(-l2 * q.step);
  for (int k = 1; k <= (1 << 22); ++k) {
    const double a1 = 0.5 * b * e1 * m1, a2 = 0.5 * (1 - b) * e2 * m2;
    if (a1 < 1e-17 * a2 && r2 < 1) {
      // Only the wide component is left: a geometric series A r^i, whose
      // entropy sums in closed form (the narrow one would need 10^6 cells).
      const double lr = std::log2(r2);
      out.rate += 2 * (-a2 * std::log2(a2) / (1 - r2) -
                       a2 * lr * r2 / ((1 - r2) * (1 - r2)));
      break;
    }
    const double pk = a1 + a2;
    out.rate += 2 * Entropy(pk);
    if (pk < 1e-18) break;
    e1 *= r1;
    e2 *= r2;
  }
  return out;
}

DrPoint ObservedDistortionRate(std::span<const double> x, const EdsqLevel& q) {
  DrPoint out;
  if (x.empty()) return out;
  std::unordered_map<int64_t, size_t> counts;
  for (double v : x) {
    const double f = std::floor(std::fabs(v) / q.step + q.xi);
    const int64_t m = f > 0 ? static_cast<int64_t>(f) : 0;
    double r = 0;
    if (m > 0) r = (static_cast<double>(m) + 0.5 - q.xi) * q.step;
    const double e = std::fabs(v) - r;
    out.distortion += e * e;
    ++counts[v < 0 ? -m : m];
  }
  const double n = static_cast<double>(x.size());
  out.distortion /= n;
  for (const auto& [symbol, count] : counts) {
    out.rate += Entropy(static_cast<double>(count) / n);
  }
  return out;
}

double ModellingErrorPercent(const std::vector<DrPoint>& model,
                             const std::vector<DrPoint>& observed) {
  std::vector<double> rm, dm, re, de;
  SortedCurve(model, rm, dm);
  SortedCurve(observed, re, de);
  if (rm.size() < 2 || re.size() < 2) return kNaN;
  const double lo = std::max(rm.front(), re.front());
  const double hi = std::min(rm.back(), re.back());
  if (!(hi > lo)) return kNaN;
  // Trapezoid rule on a fine uniform grid of the common range.
  constexpr int kSteps = 1024;
  double num = 0, den = 0;
  for (int i = 0; i <= kSteps; ++i) {
    const double r = lo + (hi - lo) * i / kSteps;
    const double a = Interpolate(rm, dm, r), b = Interpolate(re, de, r);
    const double w = (i == 0 || i == kSteps) ? 0.5 : 1.0;
    num += w * std::fabs(a - b);
    den += w * std::max(a, b);
  }
  return den > 0 ? 100 * num / den : 0.0;
}

double SnrAtRate(const std::vector<DrPoint>& curve, double sigma2, double rate) {
  std::vector<double> r, d;
  SortedCurve(curve, r, d);
  std::vector<double> lr, snr;
  for (size_t i = 0; i < r.size(); ++i) {
    if (r[i] <= 0 || d[i] <= 0) continue;
    lr.push_back(std::log(r[i]));
    snr.push_back(10 * std::log10(sigma2 / d[i]));
  }
  if (!(rate > 0)) return kNaN;
  return Interpolate(lr, snr, std::log(rate));
}

double DeltaSnr(const LaplacianMixture& model, double z,
                const DeltaSnrOptions& options) {
  // Fine enough a finest step that quantiser 0 lies well above the rate
  // range, and enough levels that the coarsest lies below it.
  const double sigma = model.Sigma();
  double step0 = sigma * 0x1p-3;
  for (int i = 0; i < 40; ++i) {
    if (MixtureDistortionRate(model, EdsqAt(step0, 0.5, 0)).rate > options.rate_hi + 1) break;
    step0 /= 2;
  }
  const double sigma2 = sigma * sigma;
  const auto curve = [&](double zz) {
    std::vector<DrPoint> c;
    for (int n = 0; n < 64; ++n) {
      const DrPoint p = MixtureDistortionRate(model, EdsqAt(step0, XiForDeadzoneRatio(zz), n));
      c.push_back(p);
      if (p.rate < options.rate_lo / 4) break;
    }
    return c;
  };
  const std::vector<DrPoint> ref = curve(1.0), test = curve(z);
  double sum = 0;
  int count = 0;
  for (int i = 0; i < options.points; ++i) {
    const double t = options.points == 1 ? 0.0 : static_cast<double>(i) / (options.points - 1);
    const double rate = options.rate_lo * std::pow(options.rate_hi / options.rate_lo, t);
    const double a = SnrAtRate(test, sigma2, rate), b = SnrAtRate(ref, sigma2, rate);
    if (std::isnan(a) || std::isnan(b)) continue;
    sum += a - b;
    ++count;
  }
  return count > 0 ? sum / count : kNaN;
}

}  // namespace meshwave
