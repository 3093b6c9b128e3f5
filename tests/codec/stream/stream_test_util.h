// Test helpers for the coding layer: a rough semi-regular mesh and its
// encoding, and PSNR against it.
#ifndef MESHWAVE_TESTS_CODEC_STREAM_STREAM_TEST_UTIL_H_
#define MESHWAVE_TESTS_CODEC_STREAM_STREAM_TEST_UTIL_H_

#include <cmath>
#include <random>

#include "codec/test_meshes.h"
#include "meshwave/encoder.h"
#include "meshwave/semiregular.h"

namespace meshwave::testing {

// A smooth shape with some fine detail: butterfly-refined icosahedron on
// the unit sphere, bumped by a few sine waves and a little noise.
inline SemiRegularMesh BumpySphere(int levels, uint32_t seed = 1) {
  auto sr = Subdivide(Icosahedron(), levels, SubdivisionScheme::kButterfly);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 2e-3);
  for (Vec3& p : sr->positions) {
    p.normalize();
    p *= 1 + 0.05 * std::sin(5 * p.x()) * std::cos(3 * p.y()) + noise(rng);
  }
  return *sr;
}

inline double Psnr(const std::vector<Vec3>& a, const std::vector<Vec3>& b,
                   double peak) {
  double sse = 0;
  for (size_t i = 0; i < a.size(); ++i) sse += (a[i] - b[i]).squaredNorm();
  const double rms = std::sqrt(sse / static_cast<double>(a.size()));
  return rms == 0 ? 999.0 : 20 * std::log10(peak / rms);
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_STREAM_STREAM_TEST_UTIL_H_
