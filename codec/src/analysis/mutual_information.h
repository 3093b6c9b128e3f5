// Mutual information estimated by adaptive partitioning of the observation
// space (Darbellay & Vajda 1999, as used by
// Satti et al. 2011): no bin size to
// choose, every final cell holds enough points for its estimate.
#ifndef MESHWAVE_ANALYSIS_MUTUAL_INFORMATION_H_
#define MESHWAVE_ANALYSIS_MUTUAL_INFORMATION_H_

#include <cstdint>
#include <span>
#include <vector>

namespace meshwave {

// Multi-information C(X_1; ...; X_d) = sum h(X_i) - h(X_1..X_d) in bits, for
// d = 2 or 3 columns of equal length (>= 8 samples; otherwise, or with
// unequal lengths, 0). Ties are
// broken by a random order drawn from `seed`, so the result is deterministic.
// For d = 2 this is I(X_1; X_2). The samples must be finite.
double MultiInformation(const std::vector<std::span<const double>>& columns,
                        uint64_t seed = 1);

// I(X; Y) in bits.
double MutualInformation(std::span<const double> x, std::span<const double> y);
// I(X; (Y, Z)) = C(X, Y, Z) - C(Y, Z) in bits (chain rule of multi-information).
double MutualInformation(std::span<const double> x, std::span<const double> y,
                         std::span<const double> z);

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_MUTUAL_INFORMATION_H_
