#include "analysis/laplacian_mixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analysis/divergence.h"
#include "codec/analysis/test_samples_testonly.h"

namespace meshwave {
namespace {

struct MixtureCase {
  double beta, sigma1, sigma2;
};

class EmRecoveryTest : public ::testing::TestWithParam<MixtureCase> {};

TEST_P(EmRecoveryTest, RecoversKnownParametersWithinFivePercent) {
  const MixtureCase c = GetParam();
  const auto x = testing::LaplacianMixtureSamples(200000, c.beta, c.sigma1, c.sigma2, 7);
  const Histogram h = BuildHistogram(x);
  const MixtureFit fit = FitLaplacianMixture(x, h);
  EXPECT_NEAR(fit.model.beta(), c.beta, 0.05 * c.beta);
  EXPECT_NEAR(fit.model.component1().Sigma(), c.sigma1, 0.05 * c.sigma1);
  EXPECT_NEAR(fit.model.component2().Sigma(), c.sigma2, 0.05 * c.sigma2);
  EXPECT_GT(fit.iterations, 0);
  EXPECT_LT(fit.kl, 0.05);
}

// Satti et al. 2011's usual weight 0.9 with small and large ratios (non-normal and
// normal meshes), an even mix, and a tiny scale.
INSTANTIATE_TEST_SUITE_P(Mixtures, EmRecoveryTest,
                         ::testing::Values(MixtureCase{0.9, 1.0, 10.0},
                                           MixtureCase{0.9, 0.01, 0.5},
                                           MixtureCase{0.6, 1.0, 4.0},
                                           MixtureCase{0.8, 2e-6, 3e-4}));

TEST(LaplacianMixtureTest, ComponentsAreOrderedNarrowFirst) {
  // Mostly wide samples: the narrow component gets the small weight.
  const auto x = testing::LaplacianMixtureSamples(100000, 0.2, 0.1, 3.0, 3);
  const MixtureFit fit = FitLaplacianMixture(x, BuildHistogram(x));
  EXPECT_LT(fit.model.component1().Sigma(), fit.model.component2().Sigma());
  EXPECT_NEAR(fit.model.beta(), 0.2, 0.02);
}

TEST(LaplacianMixtureTest, SurvivesABlockOfExactZeros) {
  auto x = testing::LaplacianMixtureSamples(20000, 0.9, 1.0, 5.0, 5);
  for (size_t i = 0; i < x.size(); i += 3) x[i] = 0.0;  // a third of zeros
  const MixtureFit fit = FitLaplacianMixture(x, BuildHistogram(x));
  EXPECT_TRUE(std::isfinite(fit.model.component1().Sigma()));
  EXPECT_GT(fit.model.component1().Sigma(), 0);
  EXPECT_TRUE(std::isfinite(fit.kl));
}

TEST(LaplacianMixtureTest, SingleLaplacianIsTheMaximumLikelihoodFit) {
  const auto x = testing::LaplacianMixtureSamples(200000, 1.0, 2.5, 2.5, 11);
  EXPECT_NEAR(FitLaplacian(x).Sigma(), 2.5, 0.02 * 2.5);
}

TEST(LaplacianMixtureTest, MassesAndSquaredErrorsAreConsistent) {
  const Laplacian l(1.3);
  EXPECT_NEAR(l.Mass(0, kInfinity), 0.5, 1e-15);
  EXPECT_NEAR(l.SignedMass(-kInfinity, kInfinity), 1.0, 1e-15);
  // Second moment of the half line: sigma^2 / 2.
  EXPECT_NEAR(l.SquaredError(0, kInfinity, 0), 0.5 * 1.3 * 1.3, 1e-12);
  const LaplacianMixture m(0.7, 0.5, 2.0);
  EXPECT_NEAR(m.Sigma() * m.Sigma(), 0.7 * 0.25 + 0.3 * 4.0, 1e-12);
  EXPECT_NEAR(2 * m.SquaredError(0, kInfinity, 0), m.Sigma() * m.Sigma(), 1e-12);
}

TEST(DivergenceTest, HistogramSumsToOneAndKlPrefersTheTrueModel) {
  const auto x = testing::LaplacianMixtureSamples(100000, 0.9, 1.0, 20.0, 13);
  const Histogram h = BuildHistogram(x);
  double total = 0;
  for (double p : h.probability) total += p;
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_EQ(h.inner_bins() % 2, 1u);
  const double kl_true = KlDivergence(h, LaplacianMixture(0.9, 1.0, 20.0));
  const double kl_single = KlDivergence(h, FitLaplacian(x));
  EXPECT_LT(kl_true, 0.01);
  EXPECT_GT(kl_single, 5 * kl_true);
}

}  // namespace
}  // namespace meshwave
