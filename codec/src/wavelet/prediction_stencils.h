// Prediction stencils of one level: for every odd vertex of M^{j+1} the
// level-j vertices and weights that predict it (Dyn et al. 1990,
// Zorin et al. 1996, Loop 1987; docs/CODEC.md).
#ifndef MESHWAVE_WAVELET_PREDICTION_STENCILS_H_
#define MESHWAVE_WAVELET_PREDICTION_STENCILS_H_

#include <cstdint>
#include <span>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/wavelet.h"
#include "semiregular/vertex_rings.h"
#include "wavelet/sawt_plan.h"

namespace meshwave {

// Compressed rows: stencil k reads vertices indices[offsets[k] ..
// offsets[k+1]) with weights weights[weight_start[k] ..] in the same order.
// Rows share weight runs: a level has only a handful of distinct stencils
// (8-point, boundary, one per extraordinary valence...), so the weights stay
// in L1 cache while the transform streams through the indices.
struct StencilTable {
  std::vector<uint32_t> offsets;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> weight_start;
  std::vector<double> weights;

  size_t size() const { return weight_start.size(); }
  double Weight(size_t row, size_t i) const {
    return weights[weight_start[row] + (i - offsets[row])];
  }
};

// Prediction of odd vertex k from the level's positions x.
inline Vec3 PredictWithStencil(const StencilTable& s, uint32_t k, const Vec3* x) {
  const uint32_t begin = s.offsets[k], end = s.offsets[k + 1];
  const double* w = s.weights.data() + s.weight_start[k];
  const uint32_t* idx = s.indices.data() + begin;
  Vec3 p = Vec3::Zero();
  for (uint32_t i = 0; i < end - begin; ++i) p += w[i] * x[idx[i]];
  return p;
}

// `rings` are the one-rings of M^j. Weights of every stencil sum to 1.
StencilTable BuildPredictionStencils(const SemiRegularHierarchy& hierarchy,
                                     int j, const VertexRings& rings,
                                     Predictor predictor);

// SAWT stencils: edge k of M^j is predicted by filter_of_edge[k] (SAWT, Denis et al. 2010a).
// Interior edges: the filter as written, wings reflected where missing.
// Boundary edges (no c4): f1 and f2 become their curve rules along the
// boundary, 1/2 + w on the endpoints and -w on the boundary neighbours
// beyond (w = 1/16: the 4-point rule; w = 1/8), and f3..f6 the midpoint,
// which is what they give with c4 reflected to c1 + c2 - c3.
StencilTable BuildSawtStencils(const SemiRegularHierarchy& hierarchy, int j,
                               const VertexRings& rings,
                               std::span<const SawtFilter> filter_of_edge);

// The update weights (w_a, w_b) of every odd vertex of level j+1, for the
// two endpoints of its edge; empty for UpdateWeights::kNone.
std::vector<std::array<double, 2>> BuildUpdateWeights(
    const SemiRegularHierarchy& hierarchy, int j, const VertexRings& rings,
    UpdateWeights update);

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_PREDICTION_STENCILS_H_
