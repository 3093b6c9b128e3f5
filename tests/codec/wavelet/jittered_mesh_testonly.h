// A semi-regular mesh with rough geometry for transform tests: a base mesh
// butterfly-subdivided, then every vertex jittered (so that no predictor is
// exact and every detail coefficient is non-zero).
#ifndef MESHWAVE_TESTS_CODEC_WAVELET_JITTERED_MESH_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_WAVELET_JITTERED_MESH_TESTONLY_H_

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave::testing {

inline SemiRegularMesh Jittered(const TriMesh& base, int levels, uint32_t seed) {
  auto sr = Subdivide(base, levels, SubdivisionScheme::kButterfly);
  EXPECT_TRUE(sr.ok()) << sr.status().ToString();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Vec3& p : sr->positions) p += Vec3(u(rng), u(rng), u(rng));
  return *sr;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_WAVELET_JITTERED_MESH_TESTONLY_H_
