#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/test_meshes.h"
#include "meshwave/analysis.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"

namespace meshwave {
namespace {

// A bumpy torus, butterfly-subdivided 4 times and perturbed, so every
// subband holds real detail.
Pyramid BumpyTorusPyramid() {
  auto mesh = Subdivide(testing::Torus(8, 6), 4, SubdivisionScheme::kButterfly);
  EXPECT_TRUE(mesh.ok());
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0, 0.01);
  for (Vec3& p : mesh->positions) p += Vec3(g(rng), g(rng), g(rng));
  auto t = WaveletTransform::Create(mesh->hierarchy, TransformSettings{});
  EXPECT_TRUE(t.ok());
  return t->Forward(mesh->positions);
}

TEST(PyramidAnalysisTest, ReportsEveryComponentOfTheFinestSubbands) {
  const Pyramid pyramid = BumpyTorusPyramid();
  AnalysisOptions options;
  options.subbands = 2;
  auto analysis = AnalyzePyramid(pyramid, options);
  ASSERT_TRUE(analysis.ok()) << analysis.status().message();
  ASSERT_EQ(analysis->components.size(), 6u);  // 2 subbands x 3 components
  EXPECT_EQ(analysis->components.front().subband, 3);
  for (const ComponentAnalysis& a : analysis->components) {
    EXPECT_EQ(a.samples, pyramid.subbands[static_cast<size_t>(a.subband)].size());
    EXPECT_LE(a.lm_sigma1, a.lm_sigma2);
    EXPECT_GT(a.gg_alpha, 0);
    for (const ModelFitQuality& f : a.fit) {
      EXPECT_TRUE(std::isfinite(f.kl_bits));
      EXPECT_GE(f.kl_bits, 0);
      EXPECT_TRUE(std::isfinite(f.me_percent));
    }
    EXPECT_EQ(a.bin_centre.size(), a.observed_density.size());
    EXPECT_EQ(a.observed_dr.size(), a.model_dr[1].size());
  }
  ASSERT_EQ(analysis->mutual_information.size(), 6u);
  for (const MutualInformationResult& m : analysis->mutual_information) {
    EXPECT_GE(m.subband, 1);
    EXPECT_TRUE(std::isfinite(m.composite));
  }
}

TEST(PyramidAnalysisTest, RejectsAPyramidWithoutSubbands) {
  Pyramid empty;
  EXPECT_FALSE(AnalyzePyramid(empty).ok());
}

TEST(DeadzoneChoiceTest, FollowsTheSeedsThresholds) {
  EXPECT_EQ(DeadzoneCodeForSigmaRatio(10), 1);   // UEQ
  EXPECT_EQ(DeadzoneCodeForSigmaRatio(200), 2);  // z = 1.5
  EXPECT_EQ(DeadzoneCodeForSigmaRatio(400), 0);  // SAQ
  EXPECT_EQ(DeadzoneCodeForSigmaRatio(900), 3);  // z = 2.5
  EXPECT_EQ(DeadzoneCodeForSigmaRatio(std::nan("")), 1);
}

}  // namespace
}  // namespace meshwave
