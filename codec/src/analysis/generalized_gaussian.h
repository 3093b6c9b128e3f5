// The zero-mean generalized Gaussian model of wavelet coefficients (seed
// eq. 17), the usual model the Laplacian mixture is compared with, and its
// brute-force fit by minimum KL divergence (Satti et al. 2011).
#ifndef MESHWAVE_ANALYSIS_GENERALIZED_GAUSSIAN_H_
#define MESHWAVE_ANALYSIS_GENERALIZED_GAUSSIAN_H_

#include <span>

#include "analysis/divergence.h"
#include "analysis/source_model.h"

namespace meshwave {

// f(x) = alpha nu^(1/alpha) / (2 Gamma(1/alpha)) exp(-nu |x|^alpha) with
// nu = (Gamma(3/alpha) / (sigma^2 Gamma(1/alpha)))^(alpha/2): alpha = 1 is
// the Laplacian, alpha = 2 the Gaussian. Masses and moments are closed forms
// in the regularized incomplete gamma function (Boost.Math).
class GeneralizedGaussian final : public SourceModel {
 public:
  GeneralizedGaussian(double sigma, double alpha);
  double Mass(double a, double b) const override;
  double SquaredError(double a, double b, double r) const override;
  double Sigma() const override { return sigma_; }
  double alpha() const { return alpha_; }
  double Pdf(double x) const;

 private:
  // int_a^b x^m f(x) dx for 0 <= a <= b, m = 0, 1, 2.
  double PartialMoment(int m, double a, double b) const;

  double sigma_, alpha_, nu_;
};

struct GgFit {
  GeneralizedGaussian model{1, 1};
  double kl = 0;  // bits
};

// Brute force (Satti et al. 2011, section 3.2): a grid over alpha in [0.1, 2] and sigma around the
// sample deviation, then a finer grid around the best point; the pair with
// the smallest KL(histogram || model) wins.
GgFit FitGeneralizedGaussian(std::span<const double> x, const Histogram& histogram);

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_GENERALIZED_GAUSSIAN_H_
