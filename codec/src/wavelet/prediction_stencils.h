// Prediction stencils of one level: for every odd vertex of M^{j+1} the
// level-j vertices and weights that predict it (CODEC_NOTES 2.2-2.3).
#ifndef MESHWAVE_WAVELET_PREDICTION_STENCILS_H_
#define MESHWAVE_WAVELET_PREDICTION_STENCILS_H_

#include <cstdint>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/wavelet.h"
#include "semiregular/vertex_rings.h"

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

// `rings` are the one-rings of M^j. Weights of every stencil sum to 1.
StencilTable BuildPredictionStencils(const SemiRegularHierarchy& hierarchy,
                                     int j, const VertexRings& rings,
                                     Predictor predictor);

// The update weights (w_a, w_b) of every odd vertex of level j+1, for the
// two endpoints of its edge; empty for UpdateWeights::kNone.
std::vector<std::array<double, 2>> BuildUpdateWeights(
    const SemiRegularHierarchy& hierarchy, int j, const VertexRings& rings,
    UpdateWeights update);

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_PREDICTION_STENCILS_H_
