// Laplacian and two-component Laplacian mixture models of wavelet
// coefficients and their EM fit (Satti et al. 2011; EM:
// Dempster et al. 1977).
#ifndef MESHWAVE_ANALYSIS_LAPLACIAN_MIXTURE_H_
#define MESHWAVE_ANALYSIS_LAPLACIAN_MIXTURE_H_

#include <span>

#include "analysis/divergence.h"
#include "analysis/source_model.h"

namespace meshwave {

// f_L(x) = (lambda / 2) exp(-lambda |x|), lambda = sqrt(2) / sigma (eq. 18).
class Laplacian final : public SourceModel {
 public:
  explicit Laplacian(double sigma) : sigma_(sigma), lambda_(std::sqrt(2.0) / sigma) {}
  double Mass(double a, double b) const override;
  double SquaredError(double a, double b, double r) const override;
  double Sigma() const override { return sigma_; }
  double lambda() const { return lambda_; }
  double Pdf(double x) const { return 0.5 * lambda_ * std::exp(-lambda_ * std::fabs(x)); }

 private:
  double sigma_, lambda_;
};

// f_LM = beta f_L(sigma1) + (1 - beta) f_L(sigma2) (eq. 19); after a fit,
// sigma1 <= sigma2, so beta is the weight of the narrow component.
class LaplacianMixture final : public SourceModel {
 public:
  LaplacianMixture(double beta, double sigma1, double sigma2)
      : beta_(beta), narrow_(sigma1), wide_(sigma2) {}
  double Mass(double a, double b) const override;
  double SquaredError(double a, double b, double r) const override;
  double Sigma() const override;
  double Pdf(double x) const {
    return beta_ * narrow_.Pdf(x) + (1 - beta_) * wide_.Pdf(x);
  }
  double beta() const { return beta_; }
  const Laplacian& component1() const { return narrow_; }
  const Laplacian& component2() const { return wide_; }

 private:
  double beta_;
  Laplacian narrow_, wide_;
};

// int_0^u (w - s)^2 e^{-w} dw for 0 <= u <= +infinity: the squared error of
// an exponential density over one quantiser cell, in units of its scale.
// Summed as a power series for u <= 1, where the closed form cancels (the
// result is ~u^3 / 12 while its terms are ~2).
double ExponentialCellError(double u, double s);

// Maximum-likelihood single Laplacian: sigma = sqrt(2) mean |x|.
Laplacian FitLaplacian(std::span<const double> x);

struct MixtureFitOptions {
  int max_iterations = 2000;
  // EM stops when the log-likelihood gains less than this (relative).
  double tolerance = 1e-10;
  // Smallest sigma either component may take, relative to the sample
  // standard deviation: a block of exact zeros (flat regions) would
  // otherwise drive one component's sigma to 0 (a floor on each
  // variance).
  double min_sigma_fraction = 1e-6;
};

struct MixtureFit {
  LaplacianMixture model{1, 1, 1};
  int iterations = 0;  // EM iterations run
  int best_iteration = 0;  // the one whose model is returned
  double kl = 0;       // KL(histogram || model) of the returned model, bits
};

// EM fit of the mixture (Satti et al. 2011): starts from sigma1^2 = sigma_E^2 / 2,
// sigma2^2 = 2 sigma_E^2, beta = 0.9; E- and M-steps in tandem until the
// likelihood converges, returning the iterate with the smallest KL
// divergence from `histogram` (Satti et al. 2011's stopping criterion; the start
// counts as iterate 0). Densities are evaluated in the log domain. `x` must
// be non-empty and finite; all-zero data give sigma = the floor.
MixtureFit FitLaplacianMixture(std::span<const double> x, const Histogram& histogram,
                               const MixtureFitOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_LAPLACIAN_MIXTURE_H_
