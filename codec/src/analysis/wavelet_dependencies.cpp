#include "analysis/wavelet_dependencies.h"

#include <cassert>

namespace meshwave {

DependencySamples GatherDependencies(const Pyramid& pyramid, int j, int component,
                                     size_t max_samples) {
  assert(j >= 1 && j < pyramid.levels());
  const SemiRegularHierarchy& h = *pyramid.hierarchy;
  const auto& band = pyramid.subbands[static_cast<size_t>(j)];
  const auto& coarser = pyramid.subbands[static_cast<size_t>(j - 1)];
  const auto& edge_faces = h.edge_faces(j);
  const auto& face_edges = h.face_edges(j);
  const size_t n = band.size();
  const size_t stride = max_samples == 0 ? 1 : (n + max_samples - 1) / max_samples;
  DependencySamples out;
  for (size_t k = 0; k < n; k += stride) {
    double t = 0;
    for (uint32_t f : edge_faces[k]) {
      if (f == SemiRegularHierarchy::kNone) continue;
      for (uint32_t e : face_edges[f]) {
        if (e != k) t += band[e][component] * band[e][component];
      }
    }
    out.x.push_back(band[k][component]);
    out.parent.push_back(coarser[h.Parent(j, static_cast<uint32_t>(k))][component]);
    out.neighbourhood.push_back(t);
  }
  return out;
}

}  // namespace meshwave
