#include "analysis/divergence.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace meshwave {

double Histogram::Lower(size_t i) const {
  if (i == 0) return -kInfinity;
  return -limit + static_cast<double>(i - 1) * width;
}

double Histogram::Upper(size_t i) const {
  if (i + 1 == probability.size()) return kInfinity;
  return -limit + static_cast<double>(i) * width;
}

Histogram BuildHistogram(std::span<const double> x) {
  assert(!x.empty());
  std::vector<double> magnitude(x.size());
  for (size_t i = 0; i < x.size(); ++i) magnitude[i] = std::fabs(x[i]);
  const size_t q = std::min(x.size() - 1,
                            static_cast<size_t>(0.999 * static_cast<double>(x.size())));
  std::nth_element(magnitude.begin(), magnitude.begin() + static_cast<ptrdiff_t>(q),
                   magnitude.end());
  Histogram h;
  h.limit = magnitude[q] > 0 ? magnitude[q] : 1.0;
  const double n = static_cast<double>(x.size());
  size_t bins = static_cast<size_t>(2.0 * std::cbrt(n));
  bins = std::clamp<size_t>(bins | 1u, 15, 201);
  h.width = 2 * h.limit / static_cast<double>(bins);
  h.probability.assign(bins + 2, 0.0);
  h.samples = x.size();
  for (double v : x) {
    size_t i;
    if (v < -h.limit) {
      i = 0;
    } else if (v >= h.limit) {
      i = bins + 1;
    } else {
      i = 1 + std::min(bins - 1, static_cast<size_t>((v + h.limit) / h.width));
    }
    h.probability[i] += 1.0;
  }
  for (double& p : h.probability) p /= n;
  return h;
}

double KlDivergence(const Histogram& observed, const SourceModel& model) {
  double kl = 0;
  for (size_t i = 0; i < observed.probability.size(); ++i) {
    const double p = observed.probability[i];
    if (p <= 0) continue;
    const double m =
        std::max(1e-300, model.SignedMass(observed.Lower(i), observed.Upper(i)));
    kl += p * std::log2(p / m);
  }
  return kl;
}

}  // namespace meshwave
