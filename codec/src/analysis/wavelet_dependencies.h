// The samples behind the dependency analysis of Satti et al.
// 2011: each coefficient
// X of a subband with its parent P_X (interband) and the summary
// T = sum n_i^2 of its neighbours in the same subband (intraband, eq. 25).
#ifndef MESHWAVE_ANALYSIS_WAVELET_DEPENDENCIES_H_
#define MESHWAVE_ANALYSIS_WAVELET_DEPENDENCIES_H_

#include <cstddef>
#include <vector>

#include "meshwave/wavelet.h"

namespace meshwave {

struct DependencySamples {
  std::vector<double> x, parent, neighbourhood;
};

// Component `component` of subband j >= 1 of `pyramid`. Neighbours of the
// coefficient on edge k of M^j: the coefficients of the same subband in its
// one-ring in M^{j+1}, i.e. on the other edges of the faces beside edge k
// (4 inside, 2 on a boundary). The parent is
// hierarchy.Parent(j, k) (docs/CODEC.md), same component, signed. With
// more than `max_samples` coefficients, every ceil(n / max_samples)-th one
// is taken.
DependencySamples GatherDependencies(const Pyramid& pyramid, int j, int component,
                                     size_t max_samples);

}  // namespace meshwave

#endif  // MESHWAVE_ANALYSIS_WAVELET_DEPENDENCIES_H_
