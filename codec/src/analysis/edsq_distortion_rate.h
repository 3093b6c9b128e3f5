// Distortion and rate of embedded deadzone scalar quantisers (EDSQ,
// Satti et al. 2011, eq. 16) on a source model or on observed data: the closed forms for a
// Laplacian (Satti et al. 2011, appendix), the Laplacian mixture (eq. 20 and
// the cell-mass sum of 3.3), the modelling error ME(%) of eq. 21 and the
// SNR gap between quantisers of Fig. 7 (Satti et al. 2011).
#ifndef MESHWAVE_ANALYSIS_EDSQ_DISTORTION_RATE_H_
#define MESHWAVE_ANALYSIS_EDSQ_DISTORTION_RATE_H_

#include <algorithm>
#include <span>
#include <vector>

#include "analysis/laplacian_mixture.h"
#include "analysis/source_model.h"

namespace meshwave {

// Quantiser n of the family: step Delta_n = 2^n Delta_0, xi_n = xi_0 / 2^n.
// Its deadzone is [-delta Delta, delta Delta] with delta = 1 - xi; cell k >= 1
// is [(k - 1 + delta) Delta, (k + delta) Delta), reconstructed at its midpoint.
struct EdsqLevel {
  double step = 1;
  double xi = 0;
  double delta() const { return 1 - xi; }
};
EdsqLevel EdsqAt(double step0, double xi0, int n);
// z = deadzone / step at the finest level = 2 (1 - xi0).
inline double XiForDeadzoneRatio(double z) { return 1 - z / 2; }

// Eq. 28: MSE per sample of a Laplacian (parameter lambda = sqrt(2)/sigma),
// evaluated in a regrouped form that keeps full precision at any rate.
double LaplacianEdsqDistortion(double lambda, const EdsqLevel& q);
// Eq. 28 exactly as printed; loses digits when Delta << sigma.
double LaplacianEdsqDistortionEq28(double lambda, const EdsqLevel& q);
// Eq. 29: entropy of the quantiser output in bits per sample.
double LaplacianEdsqRate(double lambda, const EdsqLevel& q);

struct DrPoint {
  double rate = 0;        // bits per sample (entropy of the indices)
  double distortion = 0;  // mean squared error per sample
};

// Any model, by summing over the quantiser's cells (truncated once a cell's
// mass falls below 1e-18; at most 2^22 cells).
DrPoint ModelDistortionRate(const SourceModel& model, const EdsqLevel& q);
// The mixture: D by eq. 20 over eq. 28, R from the exact cell masses (3.3).
DrPoint MixtureDistortionRate(const LaplacianMixture& model, const EdsqLevel& q);
// Observed: quantise `x` (eq. 16), midpoint reconstruction, empirical
// entropy of the signed indices.
DrPoint ObservedDistortionRate(std::span<const double> x, const EdsqLevel& q);

// The points of quantisers n = 0 .. levels - 1 of the family (step0, xi0),
// computed by `point(level)`.
template <typename F>
std::vector<DrPoint> DrCurve(double step0, double xi0, int levels, F point) {
  std::vector<DrPoint> out;
  out.reserve(static_cast<size_t>(std::max(levels, 0)));
  for (int n = 0; n < levels; ++n) out.push_back(point(EdsqAt(step0, xi0, n)));
  return out;
}

// Eq. 21 in percent: integral over the common rate range of |D_M - D_E|
// divided by the integral of max(D_M, D_E), both curves linearly
// interpolated in the rate. NaN when the rate ranges do not overlap.
double ModellingErrorPercent(const std::vector<DrPoint>& model,
                             const std::vector<DrPoint>& observed);

// SNR = 10 log10(sigma^2 / D) of a curve at `rate`, interpolated linearly
// in log(rate) between its points; NaN outside the curve.
double SnrAtRate(const std::vector<DrPoint>& curve, double sigma2, double rate);

struct DeltaSnrOptions {
  // The rate range R of the average, bits per sample, and its points
  // (spaced evenly in log rate).
  double rate_lo = 0.05;
  double rate_hi = 2.0;
  int points = 64;
};
// As in Satti et al. 2011: mean over the rate range of SNR_z(R) - SNR_{z=1}(R) for the
// mixture `model` quantised by the EDSQ of deadzone ratio z, in dB.
double DeltaSnr(const LaplacianMixture& model, double z,
                const DeltaSnrOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_EDSQ_DISTORTION_RATE_H_
