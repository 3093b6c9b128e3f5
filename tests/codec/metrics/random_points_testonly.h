// Points drawn uniformly from the cube [-range, range]^3, reproducibly.
#ifndef MESHWAVE_TESTS_CODEC_METRICS_RANDOM_POINTS_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_METRICS_RANDOM_POINTS_TESTONLY_H_

#include <cstdint>
#include <random>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::testing {

inline std::vector<Vec3> RandomPoints(size_t n, double range, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coord(-range, range);
  std::vector<Vec3> out(n);
  for (Vec3& p : out) p = Vec3(coord(rng), coord(rng), coord(rng));
  return out;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_METRICS_RANDOM_POINTS_TESTONLY_H_
