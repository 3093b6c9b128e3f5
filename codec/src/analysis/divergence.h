// Observed histograms of wavelet coefficients and their Kullback-Leibler
// divergence from a fitted model (Satti et al. 2011, Tables 1-2).
#ifndef MESHWAVE_ANALYSIS_DIVERGENCE_H_
#define MESHWAVE_ANALYSIS_DIVERGENCE_H_

#include <span>
#include <vector>

#include "analysis/source_model.h"

namespace meshwave {

// Bins of equal width over [-limit, limit] (an odd count, so one bin is
// centred on 0 where the peak of every model is), plus the two tails
// (-inf, -limit) and (limit, inf) so that both the observed and the model
// probabilities sum to 1.
struct Histogram {
  double limit = 0;
  double width = 0;
  std::vector<double> probability;  // [0]: lower tail, back(): upper tail
  size_t samples = 0;

  size_t inner_bins() const { return probability.size() - 2; }
  // [lo, hi) of bin i (tails included, as infinite ends).
  double Lower(size_t i) const;
  double Upper(size_t i) const;
  double Centre(size_t i) const { return 0.5 * (Lower(i) + Upper(i)); }
};

// The histogram of `x`: the range is the 99.9 % quantile of |x| (a few
// outliers would otherwise squeeze the peak into one bin) and the bin count
// grows like 2 N^(1/3) (Terrell-Scott's oversmoothed rule), odd, 15 to 201.
// `x` must be non-empty and finite; an all-zero `x` gets limit 1.
Histogram BuildHistogram(std::span<const double> x);

// KL(observed || model) in bits: sum over bins of H_k log2(H_k / M_k), M_k
// the model's mass of bin k. Bins the data leave empty add nothing; a bin
// with data but (numerically) no model mass is charged as if M_k = 1e-300.
double KlDivergence(const Histogram& observed, const SourceModel& model);

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_DIVERGENCE_H_
