// WaveletTransform::Forward, the analysis: the encoder's half of the
// transform (meshwave_codec); the inverse, which the decoder needs, is in
// wavelet_transform.cpp.
#include "meshwave/wavelet.h"
#include "wavelet/local_frames.h"
#include "wavelet/prediction_stencils.h"
#include "wavelet/transform_levels.h"

namespace meshwave {

Pyramid WaveletTransform::Forward(std::span<const Vec3> positions) const {
  Pyramid pyramid;
  Forward(positions, pyramid);
  return pyramid;
}

void WaveletTransform::Forward(std::span<const Vec3> positions,
                               Pyramid& pyramid) const {
  const SemiRegularHierarchy& h = *hierarchy_;
  const int num_levels = h.levels();
  // Work in place in `x`: each level's odd slots first receive the detail
  // in xyz, which is then moved to its subband (in the local frame).
  std::vector<Vec3>& x = pyramid.base;
  x.assign(positions.begin(), positions.end());
  x.resize(h.vertex_count(num_levels));
  pyramid.hierarchy = hierarchy_;
  pyramid.settings = settings_;
  pyramid.subbands.resize(num_levels);
  for (int j = num_levels - 1; j >= 0; --j) {
    const Level& level = levels_->Get(j);
    const uint32_t vj = h.vertex_count(j);
    const uint32_t n = static_cast<uint32_t>(h.subband_size(j));
    Vec3* odd = x.data() + vj;
    for (uint32_t k = 0; k < n; ++k) {
      odd[k] -= PredictWithStencil(level.stencils, k, x.data());
    }
    if (!level.update.empty()) {
      const auto& edges = h.edges(j);
      for (uint32_t k = 0; k < n; ++k) {
        x[edges[k][0]] += level.update[k][0] * odd[k];
        x[edges[k][1]] += level.update[k][1] * odd[k];
      }
    }
    std::vector<Vec3>& d = pyramid.subbands[j];
    d.resize(n);
    if (settings_.frames == FrameMode::kLocal) {
      const LevelFrames frames(h, j, std::span<const Vec3>(x.data(), vj),
                                FaceNormalScratch());
      for (uint32_t k = 0; k < n; ++k) d[k] = frames(k).ToLocal(odd[k]);
    } else {
      std::copy(odd, odd + n, d.begin());
    }
  }
  x.resize(h.vertex_count(0));
}

}  // namespace meshwave
