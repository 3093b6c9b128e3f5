// The stream with precincts that the precinct and region-order tests share:
// a bumpy sphere over 320 base faces, three levels finer (7,680
// coefficients in the finest subband), with small precincts so that the
// finest subband has tens of them.
#ifndef MESHWAVE_TESTS_CODEC_STREAM_PRECINCT_STREAM_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_STREAM_PRECINCT_STREAM_TESTONLY_H_

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/stream/stream_test_util.h"
#include "meshwave/encoder.h"
#include "meshwave/subdivision.h"

namespace meshwave::testing {

inline SemiRegularMesh FineBaseSphere() {
  TriMesh coarse = Subdivide(Icosahedron(), 2, SubdivisionScheme::kButterfly)->Finest();
  for (Vec3& p : coarse.positions) p.normalize();
  auto sr = Subdivide(coarse, 3, SubdivisionScheme::kButterfly);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 2e-3);
  for (Vec3& p : sr->positions) {
    p.normalize();
    p *= 1 + 0.05 * std::sin(5 * p.x()) * std::cos(3 * p.y()) + noise(rng);
  }
  return *sr;
}

// Precincts of at least 256 coefficients, split where they average 8 bytes.
inline const EncodedStream& Precincted() {
  static const EncodedStream s = [] {
    EncodeOptions options = EqualStepOptions();
    options.precinct_coefficients = 256;
    options.split_bytes_per_precinct = 8;
    auto encoded = EncodeMesh(FineBaseSphere(), options);
    EXPECT_TRUE(encoded.ok()) << encoded.status().ToString();
    return *std::move(encoded);
  }();
  return s;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_STREAM_PRECINCT_STREAM_TESTONLY_H_
