// Choosing the number of levels J and of base faces N of a remesh from the
// input size, so the finest level has about as many vertices as the input.
#ifndef MESHWAVE_REMESH_LEVEL_PLAN_H_
#define MESHWAVE_REMESH_LEVEL_PLAN_H_

#include <cstddef>
#include <cstdint>

#include "meshwave/status.h"

namespace meshwave::remesh {

struct LevelPlan {
  int levels = 0;
  size_t base_faces = 0;
};

// levels and base_faces as in RemeshOptions (-1: choose). A closed mesh has
// V_J ≈ V_0 + F_0 (4^J - 1) / 2 ≈ F_0 · 4^J / 2 vertices at level J, so
// N ≈ 2·V / 4^J. Automatic J is the largest in [2, 4] that leaves at least
// kMinAutoBaseFaces base faces (a coarser base loses thin parts before
// subdivision can bring them back), or 5 when even that leaves 4x as many.
// Errors: levels outside [1, 8] or base_faces < 1 when given.
Result<LevelPlan> PlanLevels(size_t input_vertices, int levels, int base_faces);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_LEVEL_PLAN_H_
