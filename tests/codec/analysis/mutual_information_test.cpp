#include "analysis/mutual_information.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace meshwave {
namespace {

struct Pair {
  std::vector<double> x, y;
};

Pair CorrelatedGaussians(size_t n, double rho, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  Pair p;
  for (size_t i = 0; i < n; ++i) {
    const double a = g(rng), b = g(rng);
    p.x.push_back(a);
    p.y.push_back(rho * a + std::sqrt(1 - rho * rho) * b);
  }
  return p;
}

class GaussianMiTest : public ::testing::TestWithParam<double> {};

TEST_P(GaussianMiTest, MatchesTheAnalyticValueWithinTwoHundredthsOfABit) {
  const double rho = GetParam();
  const Pair p = CorrelatedGaussians(20000, rho, 5);
  const double truth = -0.5 * std::log2(1 - rho * rho);
  EXPECT_NEAR(MutualInformation(p.x, p.y), truth, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Correlations, GaussianMiTest,
                         ::testing::Values(0.0, 0.3, 0.5, 0.8, 0.95));

TEST(MutualInformationTest, InvariantUnderMonotoneMaps) {
  // The estimator works on ranks, so increasing maps change nothing.
  const Pair p = CorrelatedGaussians(5000, 0.7, 9);
  std::vector<double> cx, ey;
  for (double v : p.x) cx.push_back(v * v * v);
  for (double v : p.y) ey.push_back(std::exp(v));
  EXPECT_DOUBLE_EQ(MutualInformation(p.x, p.y), MutualInformation(cx, ey));
}

TEST(MutualInformationTest, CompositeMatchesTheGaussianRegression) {
  // X = 0.6 Y + 0.6 Z + 0.8 N with Y, Z, N independent standard normals:
  // I(X; (Y, Z)) = 1/2 log2(var X / 0.64).
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0, 1);
  std::vector<double> x, y, z;
  for (int i = 0; i < 30000; ++i) {
    y.push_back(g(rng));
    z.push_back(g(rng));
    x.push_back(0.6 * y.back() + 0.6 * z.back() + 0.8 * g(rng));
  }
  const double truth = 0.5 * std::log2(1.36 / 0.64);
  EXPECT_NEAR(MutualInformation(x, y, z), truth, 0.03);
  // More conditioning information never hurts (eq. 23).
  EXPECT_GT(MutualInformation(x, y, z), MutualInformation(x, y));
}

TEST(MutualInformationTest, TiesAreBrokenDeterministically) {
  std::vector<double> x(4000, 0.0), y(4000, 0.0);
  for (size_t i = 0; i < x.size(); i += 2) x[i] = static_cast<double>(i % 7);
  EXPECT_DOUBLE_EQ(MutualInformation(x, y), MutualInformation(x, y));
  EXPECT_NEAR(MutualInformation(x, y), 0.0, 0.02);  // y is constant
}

TEST(MutualInformationTest, TooFewSamplesGiveZero) {
  const std::vector<double> x = {1, 2, 3}, y = {3, 2, 1};
  EXPECT_EQ(MutualInformation(x, y), 0.0);
}

}  // namespace
}  // namespace meshwave
