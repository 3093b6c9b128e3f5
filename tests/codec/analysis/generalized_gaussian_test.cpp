#include "analysis/generalized_gaussian.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "analysis/divergence.h"
#include "analysis/laplacian_mixture.h"
#include "codec/analysis/test_samples_testonly.h"

namespace meshwave {
namespace {

TEST(GeneralizedGaussianTest, ShapeOneIsTheLaplacian) {
  const GeneralizedGaussian gg(0.8, 1.0);
  const Laplacian l(0.8);
  for (double a : {0.0, 0.1, 0.5, 2.0}) {
    for (double w : {0.05, 0.3, 1.0}) {
      EXPECT_NEAR(gg.Mass(a, a + w), l.Mass(a, a + w), 1e-12);
      EXPECT_NEAR(gg.SquaredError(a, a + w, a + w / 2),
                  l.SquaredError(a, a + w, a + w / 2), 1e-12);
    }
  }
}

TEST(GeneralizedGaussianTest, ShapeTwoIsTheGaussian) {
  const GeneralizedGaussian gg(1.5, 2.0);
  EXPECT_NEAR(gg.Mass(0, 1.5), 0.5 * std::erf(1 / std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(gg.Mass(0, kInfinity), 0.5, 1e-12);
}

TEST(GeneralizedGaussianTest, SquaredErrorMatchesNumericalIntegration) {
  using boost::math::quadrature::gauss_kronrod;
  for (double alpha : {0.3, 0.7, 1.6}) {
    const GeneralizedGaussian gg(1.0, alpha);
    const double a = 0.4, b = 0.9, r = 0.65;
    const double numeric = gauss_kronrod<double, 61>::integrate(
        [&](double x) { return (x - r) * (x - r) * gg.Pdf(x); }, a, b, 15, 1e-14);
    EXPECT_NEAR(gg.SquaredError(a, b, r), numeric, 1e-10 * numeric) << alpha;
    const double mass = gauss_kronrod<double, 61>::integrate(
        [&](double x) { return gg.Pdf(x); }, a, b, 15, 1e-14);
    EXPECT_NEAR(gg.Mass(a, b), mass, 1e-10 * mass) << alpha;
  }
}

TEST(GeneralizedGaussianTest, BruteForceFitRecoversShapeAndDeviation) {
  for (double alpha : {0.5, 1.0, 1.8}) {
    const auto x = testing::GeneralizedGaussianSamples(200000, 2.0, alpha, 17);
    const GgFit fit = FitGeneralizedGaussian(x, BuildHistogram(x));
    EXPECT_NEAR(fit.model.alpha(), alpha, 0.05 * alpha);
    EXPECT_NEAR(fit.model.Sigma(), 2.0, 0.05 * 2.0);
    EXPECT_LT(fit.kl, 0.01);
  }
}

}  // namespace
}  // namespace meshwave
