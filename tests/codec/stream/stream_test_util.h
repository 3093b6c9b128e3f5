// Test helpers for the coding layer: a rough semi-regular mesh and its
// encoding, and PSNR against it.
#ifndef MESHWAVE_TESTS_CODEC_STREAM_STREAM_TEST_UTIL_H_
#define MESHWAVE_TESTS_CODEC_STREAM_STREAM_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "codec/test_meshes.h"
#include "meshwave/encoder.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

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

// Encode options whose three detail components share one step (the default
// quantises the tangential ones 8 times coarser): a complete stream is then
// within a few finest steps of every vertex and each packet lowers the
// vertex error, the mechanics these tests pin. The default's own behaviour
// is tested against the surface (tangent_step_test.cpp).
inline EncodeOptions EqualStepOptions() {
  EncodeOptions options;
  options.tangent_step_scale = 1;
  return options;
}

// A decoder of `s`'s header (a test failure when it cannot be made).
inline std::unique_ptr<ProgressiveDecoder> DecoderOf(const EncodedStream& s) {
  auto d = ProgressiveDecoder::Create(s.header);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return std::move(d).value();
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
