// Synthetic coefficient samples for the analysis tests: Laplacian mixtures,
// generalized Gaussians and correlated Gaussians with known parameters.
#ifndef MESHWAVE_TESTS_ANALYSIS_TEST_SAMPLES_TESTONLY_H_
#define MESHWAVE_TESTS_ANALYSIS_TEST_SAMPLES_TESTONLY_H_

#include <cmath>
#include <random>
#include <vector>

namespace meshwave::testing {

// n samples of beta f_L(sigma1) + (1 - beta) f_L(sigma2).
inline std::vector<double> LaplacianMixtureSamples(size_t n, double beta, double sigma1,
                                                   double sigma2, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> x(n);
  for (double& v : x) {
    const double sigma = u(rng) < beta ? sigma1 : sigma2;
    std::exponential_distribution<double> e(std::sqrt(2.0) / sigma);
    v = (u(rng) < 0.5 ? -1 : 1) * e(rng);
  }
  return x;
}

// n samples of the generalized Gaussian of deviation sigma and shape alpha:
// |x| = (G / nu)^(1/alpha) with G ~ Gamma(1/alpha, 1).
inline std::vector<double> GeneralizedGaussianSamples(size_t n, double sigma, double alpha,
                                                      uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::gamma_distribution<double> g(1 / alpha, 1.0);
  const double nu = std::pow(std::tgamma(3 / alpha) / (sigma * sigma * std::tgamma(1 / alpha)),
                             alpha / 2);
  std::vector<double> x(n);
  for (double& v : x) v = (u(rng) < 0.5 ? -1 : 1) * std::pow(g(rng) / nu, 1 / alpha);
  return x;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_ANALYSIS_TEST_SAMPLES_TESTONLY_H_
