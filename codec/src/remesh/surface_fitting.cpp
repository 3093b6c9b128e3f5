// FitLevels: predict, project, relax and repair folds, one level at a time.
#include "remesh/surface_fitting.h"

#include <span>

#include "meshwave/wavelet.h"
#include "remesh/fit_projection.h"
#include "remesh/fit_relaxation.h"
#include "remesh/fold_repair.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {

Status FitLevels(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
                 const InputSurface& surface, const FitOptions& options,
                 std::vector<Vec3>& positions,
                 std::vector<SurfaceAnchor>& anchors, FitStats* stats) {
  FitStats local;
  const SemiRegularHierarchy& h = *hierarchy;
  const FitState state{h,         surface, options,
                       positions, anchors, stats != nullptr ? *stats : local};
  TransformSettings settings;
  settings.predictor = Predictor::kButterfly;
  settings.update = UpdateWeights::kNone;
  settings.frames = FrameMode::kGlobal;
  MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                      WaveletTransform::Create(hierarchy, settings));
  const int levels = h.levels();
  positions.resize(h.vertex_count(levels));
  anchors.resize(h.vertex_count(levels));
  // Work grows 4x per level; the fractions reported follow the faces.
  double total = 0, done = 0;
  for (int j = 1; j <= levels; ++j) {
    total += static_cast<double>(h.faces(j).size());
  }
  for (int j = 0; j < levels; ++j) {
    transform.PredictLevel(
        j, std::span<Vec3>(positions.data(), h.vertex_count(j + 1)));
    PlaceNewVertices(state, j);
    MW_ASSIGN_OR_RETURN(
        VertexRings rings,
        VertexRings::Build(h.vertex_count(j + 1), h.faces(j + 1)));
    for (int r = 0; r < options.relax_rounds; ++r) Relax(state, j + 1, rings);
    const size_t bad = FoldRepair(state).Run(j + 1, rings);
    if (j + 1 == levels) state.stats.unrepaired_faces = bad;
    done += static_cast<double>(h.faces(j + 1).size());
    if (options.progress) options.progress(j + 1, done / total);
  }
  return Status::Ok();
}

}  // namespace meshwave::remesh
