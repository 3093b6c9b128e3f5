#include "wavelet/transform_levels.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "semiregular/vertex_rings.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {

Result<WaveletTransform::Level> BuildTransformLevel(const SemiRegularHierarchy& hierarchy,
                                                   const TransformSettings& settings, int j) {
  auto rings = VertexRings::Build(hierarchy.vertex_count(j), hierarchy.faces(j));
  if (!rings.ok()) return rings.status().WithContext("level " + std::to_string(j));
  WaveletTransform::Level level;
  if (settings.predictor == Predictor::kSawt) {
    const SawtPlan& plan = *settings.sawt;
    const auto region = SawtOddVertexRegions(hierarchy, j, plan.regions.face_region);
    std::vector<SawtFilter> filter(region.size());
    for (size_t k = 0; k < region.size(); ++k) filter[k] = plan.filters[j][region[k]];
    level.stencils = BuildSawtStencils(hierarchy, j, *rings, filter);
  } else {
    level.stencils = BuildPredictionStencils(hierarchy, j, *rings, settings.predictor);
  }
  level.update = BuildUpdateWeights(hierarchy, j, *rings, settings.update);
  return level;
}

WaveletTransform::LevelTable::LevelTable(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
                                         TransformSettings settings)
    : hierarchy_(std::move(hierarchy)),
      settings_(std::move(settings)),
      slots_(std::make_unique<Slot[]>(static_cast<size_t>(hierarchy_->levels()))) {}

Status WaveletTransform::LevelTable::Build(int j) const {
  Slot& slot = slots_[j];
  if (slot.built.load(std::memory_order_acquire)) return Status::Ok();
  const std::lock_guard lock(slot.mutex);
  if (slot.built.load(std::memory_order_relaxed)) return Status::Ok();
  MW_ASSIGN_OR_RETURN(slot.level, BuildTransformLevel(*hierarchy_, settings_, j));
  slot.built.store(true, std::memory_order_release);
  return Status::Ok();
}

const WaveletTransform::Level& WaveletTransform::LevelTable::Get(int j) const {
  const Status status = Build(j);
  if (!status.ok()) throw std::logic_error("wavelet transform: " + status.ToString());
  return slots_[j].level;
}

}  // namespace meshwave
