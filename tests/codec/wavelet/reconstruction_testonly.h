// How far a transform's round trip lands from where it started: the largest
// distance between corresponding positions.
#ifndef MESHWAVE_TESTS_CODEC_WAVELET_RECONSTRUCTION_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_WAVELET_RECONSTRUCTION_TESTONLY_H_

#include <algorithm>
#include <span>

#include "meshwave/mesh.h"

namespace meshwave::testing {

inline double MaxError(std::span<const Vec3> a, std::span<const Vec3> b) {
  double e = 0;
  for (size_t i = 0; i < a.size(); ++i) e = std::max(e, (a[i] - b[i]).norm());
  return e;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_WAVELET_RECONSTRUCTION_TESTONLY_H_
