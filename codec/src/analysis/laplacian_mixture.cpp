#include "analysis/laplacian_mixture.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

namespace meshwave {

double Laplacian::Mass(double a, double b) const {
  // -expm1 keeps narrow cells near 0 accurate.
  return 0.5 * std::exp(-lambda_ * a) * -std::expm1(-lambda_ * (b - a));
}

double ExponentialCellError(double u, double s) {
  if (u > 1.0) {
    // -e^{-w} G(w) is an antiderivative, G(w) = (w-s)^2 + 2(w-s) + 2.
    const auto g = [s](double w) { return (w - s) * (w - s) + 2 * (w - s) + 2; };
    return std::isinf(u) ? g(0) : g(0) - std::exp(-u) * g(u);
  }
  // Power series of e^{-w}: sum_m (-1)^m / m! int_0^u (w - s)^2 w^m dw.
  double sum = 0, power = u;  // u^{m+1}
  double factorial = 1;       // m!
  for (int m = 0; m < 40; ++m) {
    const double term = power * (u * u / (m + 3) - 2 * s * u / (m + 2) + s * s / (m + 1)) /
                        factorial;
    sum += (m % 2 == 0) ? term : -term;
    if (std::fabs(term) < 1e-18 * std::fabs(sum)) break;
    power *= u;
    factorial *= m + 1;
  }
  return sum;
}

double Laplacian::SquaredError(double a, double b, double r) const {
  // (1/2) int_a^b (x - r)^2 lambda e^{-lambda x} dx in units of 1/lambda.
  const double l = lambda_;
  return 0.5 * std::exp(-l * a) * ExponentialCellError(l * (b - a), l * (r - a)) / (l * l);
}

double LaplacianMixture::Mass(double a, double b) const {
  return beta_ * narrow_.Mass(a, b) + (1 - beta_) * wide_.Mass(a, b);
}

double LaplacianMixture::SquaredError(double a, double b, double r) const {
  return beta_ * narrow_.SquaredError(a, b, r) +
         (1 - beta_) * wide_.SquaredError(a, b, r);
}

double LaplacianMixture::Sigma() const {
  const double s1 = narrow_.Sigma(), s2 = wide_.Sigma();
  return std::sqrt(beta_ * s1 * s1 + (1 - beta_) * s2 * s2);
}

Laplacian FitLaplacian(std::span<const double> x) {
  assert(!x.empty());
  double sum = 0;
  for (double v : x) sum += std::fabs(v);
  const double sigma = std::sqrt(2.0) * sum / static_cast<double>(x.size());
  return Laplacian(sigma > 0 ? sigma : 1e-300);
}

MixtureFit FitLaplacianMixture(std::span<const double> x, const Histogram& histogram,
                               const MixtureFitOptions& options) {
  assert(!x.empty());
  const double n = static_cast<double>(x.size());
  double mean = 0, square = 0;
  for (double v : x) {
    mean += v;
    square += v * v;
  }
  mean /= n;
  const double var = std::max(0.0, square / n - mean * mean);
  const double floor = std::max(1e-300, std::sqrt(var) * options.min_sigma_fraction);

  // The start of Satti et al. 2011.
  double beta = 0.9;
  double s1 = std::max(floor, std::sqrt(0.5 * var));
  double s2 = std::max(floor, std::sqrt(2.0 * var));

  MixtureFit best;
  best.model = LaplacianMixture(beta, s1, s2);
  best.kl = KlDivergence(histogram, best.model);
  double previous_ll = -kInfinity;
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    // E-step (log domain: sigma1 can be 1e-6 of sigma2 on normal meshes).
    const double lw1 = std::log(beta) - std::log(s1 * std::sqrt(2.0));
    const double lw2 = std::log1p(-beta) - std::log(s2 * std::sqrt(2.0));
    const double k1 = std::sqrt(2.0) / s1, k2 = std::sqrt(2.0) / s2;
    double r1_sum = 0, r1_abs = 0, r2_abs = 0, ll = 0;
    for (double v : x) {
      const double a = std::fabs(v);
      const double l1 = lw1 - k1 * a, l2 = lw2 - k2 * a;
      const double hi = std::max(l1, l2);
      const double log_sum = hi + std::log1p(std::exp(std::min(l1, l2) - hi));
      const double r1 = std::exp(l1 - log_sum);
      ll += log_sum;
      r1_sum += r1;
      r1_abs += r1 * a;
      r2_abs += (1 - r1) * a;
    }
    // M-step: the weighted ML update of each Laplacian.
    const double r2_sum = n - r1_sum;
    beta = std::clamp(r1_sum / n, 1e-9, 1 - 1e-9);
    s1 = r1_sum > 0 ? std::max(floor, std::sqrt(2.0) * r1_abs / r1_sum) : floor;
    s2 = r2_sum > 0 ? std::max(floor, std::sqrt(2.0) * r2_abs / r2_sum) : floor;

    const LaplacianMixture model(beta, s1, s2);
    const double kl = KlDivergence(histogram, model);
    if (kl < best.kl) {
      best.model = model;
      best.kl = kl;
      best.best_iteration = it + 1;
    }
    if (std::isfinite(previous_ll) &&
        std::fabs(ll - previous_ll) <= options.tolerance * std::fabs(ll)) {
      ++it;
      break;
    }
    previous_ll = ll;
  }
  best.iterations = it;
  // Relabel so that component 1 is the narrow one.
  const LaplacianMixture& m = best.model;
  if (m.component1().Sigma() > m.component2().Sigma()) {
    best.model = LaplacianMixture(1 - m.beta(), m.component2().Sigma(),
                                  m.component1().Sigma());
  }
  return best;
}

}  // namespace meshwave
