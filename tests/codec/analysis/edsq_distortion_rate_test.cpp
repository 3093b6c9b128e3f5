#include "analysis/edsq_distortion_rate.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <algorithm>
#include <cmath>

#include "analysis/generalized_gaussian.h"
#include "codec/analysis/test_samples_testonly.h"

namespace meshwave {
namespace {

using boost::math::quadrature::gauss_kronrod;

double Integrate(const auto& f, double a, double b) {
  return gauss_kronrod<double, 61>::integrate(f, a, b, 6, 1e-13);
}

// D and R of an EDSQ on a Laplacian by numerical integration of the pdf
// over every cell (the definitions in Satti et al. 2011's appendix).
DrPoint NumericLaplacian(double lambda, const EdsqLevel& q) {
  const auto pdf = [lambda](double x) { return 0.5 * lambda * std::exp(-lambda * x); };
  const double dz = q.delta() * q.step;
  const double p0 = 2 * Integrate(pdf, 0, dz);
  DrPoint out;
  out.distortion = 2 * Integrate([&](double x) { return x * x * pdf(x); }, 0, dz);
  out.rate = -p0 * std::log2(p0);
  for (int k = 1; k < 1000000; ++k) {
    const double a = (k - 1 + q.delta()) * q.step, b = a + q.step;
    const double r = (k - 0.5 + q.delta()) * q.step;
    const double pk = Integrate(pdf, a, b);
    if (pk < 1e-22) break;
    out.distortion += 2 * Integrate([&](double x) { return (x - r) * (x - r) * pdf(x); }, a, b);
    out.rate -= 2 * pk * std::log2(pk);
  }
  return out;
}

struct LaplacianCase {
  double lambda, step0;
};

class ClosedFormTest : public ::testing::TestWithParam<LaplacianCase> {};

TEST_P(ClosedFormTest, DistortionAndRateMatchNumericalIntegration) {
  const LaplacianCase c = GetParam();
  for (double xi0 : {0.5, 0.25, 0.0, -0.25, -0.5}) {
    for (int n = 0; n < 4; ++n) {
      const EdsqLevel q = EdsqAt(c.step0, xi0, n);
      const DrPoint numeric = NumericLaplacian(c.lambda, q);
      const double d = LaplacianEdsqDistortion(c.lambda, q);
      const double r = LaplacianEdsqRate(c.lambda, q);
      EXPECT_NEAR(d, numeric.distortion, 1e-6 * numeric.distortion)
          << "xi0 " << xi0 << " n " << n;
      EXPECT_NEAR(r, numeric.rate, std::max(1e-6 * numeric.rate, 1e-12))
          << "xi0 " << xi0 << " n " << n;
      // Eq. 28 as printed agrees where it is well conditioned.
      if (c.lambda * q.step > 0.05) {
        EXPECT_NEAR(LaplacianEdsqDistortionEq28(c.lambda, q), d, 1e-9 * d);
      }
      // The generic cell sum agrees too.
      const DrPoint generic = ModelDistortionRate(Laplacian(std::sqrt(2.0) / c.lambda), q);
      EXPECT_NEAR(generic.distortion, d, 1e-9 * d);
      EXPECT_NEAR(generic.rate, r, std::max(1e-9 * r, 1e-12));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Laplacians, ClosedFormTest,
                         ::testing::Values(LaplacianCase{1.3, 0.7}, LaplacianCase{28.3, 0.3},
                                           LaplacianCase{0.2, 3.0}, LaplacianCase{5.0, 0.01}));

TEST(MixtureDistortionRateTest, MatchesTheCellSumOfTheMixture) {
  for (double ratio : {3.0, 50.0, 400.0}) {
    const LaplacianMixture m(0.9, 1.0, ratio);
    for (int n = 0; n < 8; ++n) {
      const EdsqLevel q = EdsqAt(0.05, 0.25, n);
      const DrPoint closed = MixtureDistortionRate(m, q);
      const DrPoint generic = ModelDistortionRate(m, q);
      EXPECT_NEAR(closed.distortion, generic.distortion, 1e-9 * generic.distortion);
      EXPECT_NEAR(closed.rate, generic.rate, 1e-9 * generic.rate);
    }
  }
}

TEST(ObservedDistortionRateTest, ConvergesToTheModelOnItsSamples) {
  const auto x = testing::LaplacianMixtureSamples(1000000, 1.0, 1.0, 1.0, 21);
  for (int n = 0; n < 6; ++n) {
    const EdsqLevel q = EdsqAt(0.1, 0.0, n);
    const DrPoint observed = ObservedDistortionRate(x, q);
    const double lambda = std::sqrt(2.0);
    EXPECT_NEAR(observed.distortion, LaplacianEdsqDistortion(lambda, q),
                0.01 * LaplacianEdsqDistortion(lambda, q));
    EXPECT_NEAR(observed.rate, LaplacianEdsqRate(lambda, q), 0.01);
  }
}

TEST(ModellingErrorTest, ZeroForTheSameCurveAndOneThirdForTwiceTheDistortion) {
  std::vector<DrPoint> e, m;
  for (int i = 0; i < 8; ++i) {
    e.push_back({0.5 * i, std::exp(-0.7 * i)});
    m.push_back({0.5 * i, 2 * std::exp(-0.7 * i)});
  }
  EXPECT_NEAR(ModellingErrorPercent(e, e), 0.0, 1e-12);
  // |2D - D| / max(2D, D) = 1/2 everywhere.
  EXPECT_NEAR(ModellingErrorPercent(m, e), 50.0, 1e-9);
  EXPECT_TRUE(std::isnan(ModellingErrorPercent({{0, 1}, {1, 0.5}}, {{2, 1}, {3, 0.5}})));
}

TEST(DeltaSnrTest, UniformQuantizerIsTheReference) {
  const LaplacianMixture m(0.9, 1.0, 100.0);
  EXPECT_NEAR(DeltaSnr(m, 1.0), 0.0, 1e-12);
  // All five quantisers give finite gaps.
  for (double z : {1.5, 2.0, 2.5, 3.0}) EXPECT_TRUE(std::isfinite(DeltaSnr(m, z))) << z;
}

}  // namespace
}  // namespace meshwave
