#include "core/correctly_rounded_cos.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace meshwave {
namespace {

double ZorinAngle(int k, int n) { return 2 * std::numbers::pi * n / k; }

// cos of Zorin angles rounded to nearest, from 200-bit arithmetic (mpmath):
// the first three are ones glibc's std::cos rounds the other way, the next
// three ones musl's (the WebAssembly build's libm) does.
TEST(CorrectlyRoundedCosTest, MatchesHighPrecisionValues) {
  EXPECT_EQ(CorrectlyRoundedCos(ZorinAngle(52, 13)), -0x1.72cece675d1fdp-53);
  EXPECT_EQ(CorrectlyRoundedCos(ZorinAngle(61, 19)), -0x1.81c4f4fa9dc8bp-2);
  EXPECT_EQ(CorrectlyRoundedCos(2 * ZorinAngle(91, 19)), -0x1.bcdee2431fa0cp-1);
  EXPECT_EQ(CorrectlyRoundedCos(ZorinAngle(5, 3)), -0x1.9e3779b97f4a9p-1);
  EXPECT_EQ(CorrectlyRoundedCos(ZorinAngle(17, 15)), 0x1.7a5f6075d487fp-1);
  EXPECT_EQ(CorrectlyRoundedCos(ZorinAngle(23, 1)), 0x1.ed037ea3d2dbbp-1);
  EXPECT_EQ(CorrectlyRoundedCos(0.0), 1.0);
}

TEST(CorrectlyRoundedCosTest, WithinAnUlpOfStdCosOverTheRange) {
  for (double x = 0; x < 13; x += 0.001) {
    const double c = CorrectlyRoundedCos(x), s = std::cos(x);
    EXPECT_LE(std::abs(c - s), std::nextafter(std::abs(s), 2.0) - std::abs(s)) << x;
  }
}

#ifdef __GLIBC__
// What keeps native streams as they were: for every valence up to 51,
// glibc's std::cos is already the correctly rounded value.
TEST(CorrectlyRoundedCosTest, EqualsGlibcForValencesUpTo51) {
  for (int k = 3; k <= 51; ++k) {
    for (int n = 0; n < k; ++n) {
      const double a = ZorinAngle(k, n);
      EXPECT_EQ(CorrectlyRoundedCos(a), std::cos(a)) << k << " " << n;
      EXPECT_EQ(CorrectlyRoundedCos(2 * a), std::cos(2 * a)) << k << " " << n;
    }
  }
}
#endif

}  // namespace
}  // namespace meshwave
