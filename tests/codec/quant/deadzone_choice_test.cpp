#include "quant/deadzone_choice.h"

#include <gtest/gtest.h>

#include <random>

#include "codec/analysis/test_samples_testonly.h"
#include "codec/test_meshes.h"
#include "meshwave/encoder.h"
#include "meshwave/rate_distortion.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave {
namespace {

TEST(DeadzoneChoiceTest, PicksFromTheFittedSigmaRatio) {
  // beta 0.9 as in Satti et al. 2011, Fig. 7: ratio 10 -> UEQ, 400 -> SAQ, 2000 -> z = 2.5.
  EXPECT_EQ(ChooseDeadzoneCode(testing::LaplacianMixtureSamples(100000, 0.9, 1, 10, 1), 0), 1);
  EXPECT_EQ(ChooseDeadzoneCode(testing::LaplacianMixtureSamples(100000, 0.9, 1, 400, 2), 1), 0);
  EXPECT_EQ(ChooseDeadzoneCode(testing::LaplacianMixtureSamples(100000, 0.9, 1, 2000, 3), 0), 3);
}

TEST(DeadzoneChoiceTest, FallsBackOnTinyOrEmptySubbands) {
  const std::vector<double> few(10, 1.0), zeros(1000, 0.0);
  EXPECT_EQ(ChooseDeadzoneCode(few, 2), 2);
  EXPECT_EQ(ChooseDeadzoneCode(zeros, 3), 3);
}

TEST(DeadzoneChoiceTest, AutoStreamsCarryTheirDeadzonesAndDecode) {
  auto mesh = Subdivide(testing::Torus(8, 6), 3, SubdivisionScheme::kButterfly);
  ASSERT_TRUE(mesh.ok());
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g(0, 0.01);
  for (Vec3& p : mesh->positions) p += Vec3(g(rng), g(rng), g(rng));
  EncodeOptions options;
  options.auto_deadzone = true;
  auto stream = EncodeMesh(*mesh, options);
  ASSERT_TRUE(stream.ok()) << stream.status().message();
  ASSERT_EQ(stream->header.quantizers.size(), 3u * 3);
  for (const auto& q : stream->header.quantizers) EXPECT_LE(q.deadzone, 3u);
  // Gaussian noise on a smooth surface: a near-Laplacian source, UEQ.
  EXPECT_EQ(stream->header.quantizers[3 * 2].deadzone, 1u);
  // Every prefix decodes; the whole stream reaches the precision's quality.
  auto curve = MeasureRdCurve(*mesh, RdCoder::k3xC, options);
  ASSERT_TRUE(curve.ok()) << curve.status().message();
  EXPECT_GT(curve->points.back().psnr_db, 80);
}

}  // namespace
}  // namespace meshwave
