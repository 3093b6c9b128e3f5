#include "remesh/level_plan.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meshwave::remesh {
namespace {

// Measured on the shared meshes (docs/REMESH_RESULTS.md): with fewer base
// faces thin parts (ogre fingers, armadillo ears) collapse in the base and
// the Hausdorff distance grows past 1 % of the diagonal.
constexpr double kMinAutoBaseFaces = 1000;
constexpr int kMinAutoLevels = 2;
constexpr int kMaxPreferredLevels = 4;
constexpr int kMaxAutoLevels = 5;

double FacesFor(double vertices, int levels) {
  return 2 * vertices / std::pow(4.0, levels);
}

}  // namespace

Result<LevelPlan> PlanLevels(size_t input_vertices, int levels,
                             int base_faces) {
  if (levels != -1 && (levels < 1 || levels > 8)) {
    return InvalidArgument(
        "levels must be in [1, 8] (or -1 for automatic), got " +
        std::to_string(levels));
  }
  if (base_faces != -1 && base_faces < 1) {
    return InvalidArgument(
        "base faces must be at least 1 (or -1 for automatic), got " +
        std::to_string(base_faces));
  }
  const double v = static_cast<double>(std::max<size_t>(input_vertices, 3));
  LevelPlan plan;
  if (levels != -1) {
    plan.levels = levels;
  } else if (base_faces != -1) {
    // J whose finest level comes closest to the input in ratio.
    const double j = std::log(2 * v / base_faces) / std::log(4.0);
    plan.levels = std::clamp(static_cast<int>(std::lround(j)), 1, 8);
  } else {
    plan.levels = kMinAutoLevels;
    for (int j = kMinAutoLevels + 1; j <= kMaxPreferredLevels; ++j) {
      if (FacesFor(v, j) >= kMinAutoBaseFaces) plan.levels = j;
    }
    if (FacesFor(v, kMaxAutoLevels) >= 4 * kMinAutoBaseFaces) {
      plan.levels = kMaxAutoLevels;
    }
  }
  plan.base_faces = base_faces != -1
                        ? static_cast<size_t>(base_faces)
                        : static_cast<size_t>(std::max(
                              4.0, std::round(FacesFor(v, plan.levels))));
  return plan;
}

}  // namespace meshwave::remesh
