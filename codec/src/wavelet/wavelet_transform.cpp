#include <string>

#include "meshwave/wavelet.h"

#include "wavelet/local_frames.h"
#include "wavelet/prediction_stencils.h"
#include "wavelet/sawt_plan.h"
#include "wavelet/transform_levels.h"

namespace meshwave {

Result<WaveletTransform> WaveletTransform::Create(
    std::shared_ptr<const SemiRegularHierarchy> hierarchy,
    const TransformSettings& settings, Stencils when) {
  if (!hierarchy) return InvalidArgument("no hierarchy");
  const SawtPlan* plan = settings.sawt.get();
  if (settings.predictor == Predictor::kSawt) {
    if (plan == nullptr) return InvalidArgument("SAWT transform without its filter choices");
    if (plan->filters.size() != static_cast<size_t>(hierarchy->levels()) ||
        plan->regions.face_region.size() != hierarchy->faces(0).size()) {
      return InvalidArgument("SAWT filter choices do not fit the hierarchy");
    }
    for (const auto& level : plan->filters) {
      if (level.size() != plan->regions.count) {
        return InvalidArgument("SAWT filter choices: one per region and level expected");
      }
    }
    for (uint32_t r : plan->regions.face_region) {
      if (r >= plan->regions.count) return InvalidArgument("SAWT region out of range");
    }
  }
  auto table = std::make_shared<LevelTable>(hierarchy, settings);
  // Level 0 now in any case: building its one-rings is the check that the
  // base is an oriented manifold; the finer levels subdivide it and cannot fail.
  const int now = when == Stencils::kAllNow ? hierarchy->levels() : 1;
  for (int j = 0; j < now && j < hierarchy->levels(); ++j) {
    MW_RETURN_IF_ERROR(table->Build(j));
  }
  WaveletTransform t;
  t.hierarchy_ = std::move(hierarchy);
  t.settings_ = settings;
  t.levels_ = std::move(table);
  return t;
}

int WaveletTransform::levels() const { return levels_->size(); }

void WaveletTransform::PrepareLevel(int j) const { levels_->Get(j); }

std::vector<Vec3> WaveletTransform::Inverse(const Pyramid& pyramid,
                                            int max_level) const {
  std::vector<Vec3> x;
  Inverse(pyramid, max_level, x);
  return x;
}

void WaveletTransform::Inverse(const Pyramid& pyramid, int max_level,
                               std::vector<Vec3>& x) const {
  const SemiRegularHierarchy& h = *hierarchy_;
  if (max_level < 0 || max_level > levels()) max_level = levels();
  x.resize(h.vertex_count(max_level));
  std::copy(pyramid.base.begin(), pyramid.base.end(), x.begin());
  for (int j = 0; j < max_level; ++j) {
    const std::vector<Vec3>& coded = pyramid.subbands[j];
    std::copy(coded.begin(), coded.end(), x.begin() + h.vertex_count(j));
  }
  InverseInPlace(x, max_level);
}

void WaveletTransform::InverseInPlace(std::vector<Vec3>& x, int max_level) const {
  const SemiRegularHierarchy& h = *hierarchy_;
  if (max_level < 0 || max_level > levels()) max_level = levels();
  x.resize(h.vertex_count(max_level));
  for (int j = 0; j < max_level; ++j) {
    const Level& level = levels_->Get(j);
    const uint32_t vj = h.vertex_count(j);
    const uint32_t n = static_cast<uint32_t>(h.subband_size(j));
    // The odd slots hold d^j, then the detail in xyz until the prediction
    // is added. (Each frame reads only the coarse vertices [0, V_j).)
    Vec3* odd = x.data() + vj;
    if (settings_.frames == FrameMode::kLocal) {
      const LevelFrames frames(h, j, std::span<const Vec3>(x.data(), vj),
                                FaceNormalScratch());
      for (uint32_t k = 0; k < n; ++k) odd[k] = frames(k).ToGlobal(odd[k]);
    }
    if (!level.update.empty()) {
      const auto& edges = h.edges(j);
      for (uint32_t k = 0; k < n; ++k) {
        x[edges[k][0]] -= level.update[k][0] * odd[k];
        x[edges[k][1]] -= level.update[k][1] * odd[k];
      }
    }
    for (uint32_t k = 0; k < n; ++k) {
      odd[k] += PredictWithStencil(level.stencils, k, x.data());
    }
  }
}

void WaveletTransform::PredictLevel(int j, std::span<Vec3> positions) const {
  const Level& level = levels_->Get(j);
  const uint32_t vj = hierarchy_->vertex_count(j);
  const uint32_t n = static_cast<uint32_t>(hierarchy_->subband_size(j));
  for (uint32_t k = 0; k < n; ++k) {
    positions[vj + k] = PredictWithStencil(level.stencils, k, positions.data());
  }
}

Result<Predictor> ParsePredictor(const std::string& name) {
  if (name == "linear" || name == "midpoint") return Predictor::kLinear;
  if (name == "butterfly") return Predictor::kButterfly;
  if (name == "loop") return Predictor::kLoop;
  if (name == "sawt") return Predictor::kSawt;
  return InvalidArgument("unknown predictor \"" + name +
                         "\" (expected linear, butterfly, loop or sawt)");
}

const char* PredictorName(Predictor predictor) {
  switch (predictor) {
    case Predictor::kLinear: return "linear";
    case Predictor::kButterfly: return "butterfly";
    case Predictor::kLoop: return "loop";
    case Predictor::kSawt: return "sawt";
  }
  return "?";
}

Result<UpdateWeights> ParseUpdateWeights(const std::string& name) {
  if (name == "none" || name == "unlifted") return UpdateWeights::kNone;
  if (name == "constant" || name == "lifted") return UpdateWeights::kConstant;
  if (name == "valence") return UpdateWeights::kValence;
  return InvalidArgument("unknown update \"" + name +
                         "\" (expected none, constant or valence)");
}

const char* UpdateWeightsName(UpdateWeights update) {
  switch (update) {
    case UpdateWeights::kNone: return "none";
    case UpdateWeights::kConstant: return "constant";
    case UpdateWeights::kValence: return "valence";
  }
  return "?";
}

}  // namespace meshwave
