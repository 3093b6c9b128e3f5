#include "quant/deadzone_quantizer.h"

#include <gtest/gtest.h>

#include <random>

#include "quant/subband_gains.h"

namespace meshwave {
namespace {

TEST(DeadzoneQuantizerTest, CoarserLevelsAreBitplaneTruncations) {
  // Eq. 16 at level n equals Q0 >> n for every deadzone of the family.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-50, 50);
  for (int code = 0; code < 4; ++code) {
    const double xi0 = DeadzoneXi(code);
    for (int i = 0; i < 2000; ++i) {
      const double x = u(rng), step = 0.37;
      const uint32_t q0 = QuantizeMagnitude(x, step, xi0);
      for (int n = 0; n < 6; ++n) {
        const double direct = std::floor(std::fabs(x) / (step * (1 << n)) + xi0 / (1 << n));
        EXPECT_EQ(q0 >> n, direct > 0 ? static_cast<uint32_t>(direct) : 0u);
      }
    }
  }
}

TEST(DeadzoneQuantizerTest, ReconstructsAtCellMidpoint) {
  const double step = 0.5;
  for (int code = 0; code < 4; ++code) {
    const double xi0 = DeadzoneXi(code);
    for (double x = 0.01; x < 40; x += 0.173) {
      const uint32_t q0 = QuantizeMagnitude(x, step, xi0);
      for (int n = 0; n < 4; ++n) {
        const uint32_t q = q0 >> n;
        if (q == 0) continue;
        const double r = Dequantize(q, n, false, step, xi0);
        // x lies in the cell whose midpoint r is: |x - r| <= half a cell.
        EXPECT_LE(std::fabs(x - r), 0.5 * step * (1 << n) + 1e-12);
        EXPECT_LT(Dequantize(q, n, true, step, xi0), 0);
      }
    }
  }
}

TEST(DeadzoneQuantizerTest, SaqDeadzoneIsTwoSteps) {
  EXPECT_EQ(QuantizeMagnitude(0.99, 1.0, DeadzoneXi(0)), 0u);
  EXPECT_EQ(QuantizeMagnitude(-0.99, 1.0, DeadzoneXi(0)), 0u);
  EXPECT_EQ(QuantizeMagnitude(1.0, 1.0, DeadzoneXi(0)), 1u);
  EXPECT_EQ(QuantizeMagnitude(0.5, 1.0, DeadzoneXi(1)), 1u);  // UEQ rounds
  EXPECT_EQ(QuantizeMagnitude(1e300, 1.0, 0), kMaxMagnitude);
  EXPECT_EQ(TopBitplane(0), -1);
  EXPECT_EQ(TopBitplane(1), 0);
  EXPECT_EQ(TopBitplane(1023), 9);
}

TEST(SubbandGainsTest, CoarserSubbandsWeighAboutFourTimesMore) {
  const SubbandGains g = ComputeSubbandGains(TransformSettings{}, 6);
  ASSERT_EQ(g.subband.size(), 6u);
  EXPECT_DOUBLE_EQ(g.subband[5], 1.0);
  for (int j = 0; j < 5; ++j) {
    const double ratio = g.subband[j] / g.subband[j + 1];
    EXPECT_GT(ratio, 2.0) << j;
    EXPECT_LT(ratio, 6.0) << j;
  }
  EXPECT_GT(g.base, g.subband[0]);
}

}  // namespace
}  // namespace meshwave
