// The prediction stencils and update weights of every level of a
// WaveletTransform, each level built once: all at creation, or level by
// level on first use (a decoder drawing M^2 of a 4-level stream needs
// levels 0 and 1 only, and the finest level is about three quarters of the
// work). Get is safe from several threads: the first caller of a level
// builds it, the others wait for that one build.
#ifndef MESHWAVE_WAVELET_TRANSFORM_LEVELS_H_
#define MESHWAVE_WAVELET_TRANSFORM_LEVELS_H_

#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/wavelet.h"
#include "wavelet/prediction_stencils.h"

namespace meshwave {

struct WaveletTransform::Level {
  StencilTable stencils;
  std::vector<std::array<double, 2>> update;  // empty when unlifted
};

// Level j's stencils and weights; fails when M^j is not an oriented
// manifold (only M^0 can fail: finer levels are its regular subdivision).
Result<WaveletTransform::Level> BuildTransformLevel(const SemiRegularHierarchy& hierarchy,
                                                   const TransformSettings& settings, int j);

class WaveletTransform::LevelTable {
 public:
  // Builds no level yet. `settings` has been checked against `hierarchy`.
  LevelTable(std::shared_ptr<const SemiRegularHierarchy> hierarchy, TransformSettings settings);

  int size() const { return hierarchy_->levels(); }
  // Level j (< size()), built now if no caller has built it. Throws
  // std::logic_error if building fails, which Create rules out by building
  // level 0 itself.
  const Level& Get(int j) const;
  // Level j built here and now, its error returned (Create's use).
  Status Build(int j) const;

 private:
  // (A mutex and a flag rather than std::once_flag: a build that fails
  // must leave the slot to the next caller.)
  struct Slot {
    std::mutex mutex;
    std::atomic<bool> built{false};
    Level level;
  };

  std::shared_ptr<const SemiRegularHierarchy> hierarchy_;
  TransformSettings settings_;
  std::unique_ptr<Slot[]> slots_;  // mutexes move nowhere
};

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_TRANSFORM_LEVELS_H_
