// Synthesis energy gains of the subbands (docs/CODEC.md, "subband
// weighting"): an error e in one coefficient of d^j spreads over many
// vertices of M^J; its energy there is G_j e^2. Coding every subband with the
// step Δ0 / sqrt(G_j) puts all coefficients on one distortion scale, which is
// what a single bitplane threshold across subbands (quality order) and the
// packets' distortion figures assume.
#ifndef MESHWAVE_QUANT_SUBBAND_GAINS_H_
#define MESHWAVE_QUANT_SUBBAND_GAINS_H_

#include <vector>

#include "meshwave/wavelet.h"

namespace meshwave {

struct SubbandGains {
  std::vector<double> subband;  // G_0 .. G_{J-1}
  double base = 1.0;            // gain of a base vertex
};

// Gains of a J-level transform, measured with unit impulses on a regular
// (all valence 6) torus and extrapolated by 4x per level beyond 5 levels.
// Deterministic; cached per (predictor, update, J).
SubbandGains ComputeSubbandGains(const TransformSettings& settings, int levels);

}  // namespace meshwave

#endif  // MESHWAVE_QUANT_SUBBAND_GAINS_H_
