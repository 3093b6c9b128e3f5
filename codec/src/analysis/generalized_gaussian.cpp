#include "analysis/generalized_gaussian.h"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>

namespace meshwave {

GeneralizedGaussian::GeneralizedGaussian(double sigma, double alpha)
    : sigma_(sigma), alpha_(alpha) {
  const double ratio = boost::math::tgamma_ratio(3 / alpha, 1 / alpha);
  nu_ = std::pow(ratio / (sigma * sigma), alpha / 2);
}

double GeneralizedGaussian::Pdf(double x) const {
  const double norm =
      alpha_ * std::pow(nu_, 1 / alpha_) / (2 * std::tgamma(1 / alpha_));
  return norm * std::exp(-nu_ * std::pow(std::fabs(x), alpha_));
}

double GeneralizedGaussian::PartialMoment(int m, double a, double b) const {
  // Substituting t = nu x^alpha turns the integral into an incomplete gamma
  // function of shape (m + 1) / alpha.
  const double shape = (m + 1) / alpha_;
  const double scale = std::pow(nu_, -m / alpha_) *
                       boost::math::tgamma_ratio(shape, 1 / alpha_) / 2;
  const double ta = nu_ * std::pow(a, alpha_);
  if (std::isinf(b)) return scale * boost::math::gamma_q(shape, ta);
  const double tb = nu_ * std::pow(b, alpha_);
  // Upper tails subtract without cancellation far out, lower ones near 0.
  if (ta > shape) {
    return scale * (boost::math::gamma_q(shape, ta) - boost::math::gamma_q(shape, tb));
  }
  return scale * (boost::math::gamma_p(shape, tb) - boost::math::gamma_p(shape, ta));
}

double GeneralizedGaussian::Mass(double a, double b) const {
  return PartialMoment(0, a, b);
}

double GeneralizedGaussian::SquaredError(double a, double b, double r) const {
  const double e = PartialMoment(2, a, b) - 2 * r * PartialMoment(1, a, b) +
                   r * r * PartialMoment(0, a, b);
  return std::max(0.0, e);
}

GgFit FitGeneralizedGaussian(std::span<const double> x, const Histogram& histogram) {
  double square = 0;
  for (double v : x) square += v * v;
  const double sigma_e = std::sqrt(square / static_cast<double>(x.size()));
  GgFit best;
  best.kl = kInfinity;
  if (!(sigma_e > 0)) {
    best.model = GeneralizedGaussian(1e-300, 1);
    best.kl = 0;
    return best;
  }
  const auto search = [&](double a_lo, double a_hi, double a_step, double t_lo,
                          double t_hi, double t_step) {
    for (double alpha = a_lo; alpha <= a_hi + 1e-12; alpha += a_step) {
      if (alpha < 0.05 || alpha > 2.0 + 1e-12) continue;
      for (double t = t_lo; t <= t_hi + 1e-12; t += t_step) {
        const GeneralizedGaussian model(sigma_e * std::exp2(t), alpha);
        const double kl = KlDivergence(histogram, model);
        if (kl < best.kl) {
          best.kl = kl;
          best.model = model;
        }
      }
    }
  };
  search(0.1, 2.0, 0.05, -3.0, 1.0, 0.1);
  const double a0 = best.model.alpha();
  const double t0 = std::log2(best.model.Sigma() / sigma_e);
  search(a0 - 0.05, a0 + 0.05, 0.005, t0 - 0.1, t0 + 0.1, 0.01);
  return best;
}

}  // namespace meshwave
