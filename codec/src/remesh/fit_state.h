// What the stages of surface fitting (fit_projection.h, fit_relaxation.h,
// fold_repair.h) share: where each remesh vertex sits on the input, the
// options and counters of a fit, and the level state every stage reads and
// moves. Each stage is a function of a FitState, so it can be run on its
// own on a small hand-made case.
#ifndef MESHWAVE_REMESH_FIT_STATE_H_
#define MESHWAVE_REMESH_FIT_STATE_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "mesh/vertex_normals.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "remesh/boundary_loops.h"
#include "remesh/input_surface.h"

namespace meshwave::remesh {

// Where a remesh vertex sits on the input surface.
struct SurfaceAnchor {
  uint32_t face = InputSurface::kNoFace;  // input face it lies on
  uint32_t component = 0;                 // input component it belongs to
  uint32_t loop = BoundaryLoops::kNone;   // input boundary loop, if on one
  double s = 0;                           // arc length along that loop
  bool pinned = false;  // a base vertex kept on a feature: moves last
};

struct FitOptions {
  // Tangential relaxation rounds after each level, and the step (fraction
  // of the way to the one-ring centroid).
  int relax_rounds = 3;
  double relax_step = 0.5;
  // Rounds of untangling for faces that end up folded or degenerate (more
  // rounds keep helping a little on ogre.obj; 16 costs about 10 % of the
  // fitting time on igea.ply).
  int repair_rounds = 16;
  // How far along the interpolated normal a new vertex may move, as a
  // multiple of the length of the edge it splits.
  double normal_reach = 1.0;
  // The least-squares stage on the finest level (fit_least_squares.h):
  // Gauss-Newton rounds (0 turns it off), the weight of the smoothness of
  // the normal offsets, and the largest offset as a fraction of a vertex's
  // shortest edge.
  int least_squares_rounds = 1;
  double least_squares_smoothness = 0.01;
  double least_squares_max_offset = 0.25;
  int threads = 2;
  // Called after each level with (level reached, fraction of all work).
  std::function<void(int level, double fraction)> progress;
};

struct FitStats {
  size_t normal_hits = 0;        // new vertices placed along the normal
  size_t closest_fallbacks = 0;  // ... at the closest point instead
  size_t boundary_vertices = 0;  // ... on an input boundary loop
  size_t repair_moves = 0;       // moves made to untangle folds and slivers
  size_t unrepaired_faces = 0;   // folded or degenerate after the last level
};

// A fit in progress. `positions` and `anchors` hold (at least) the vertices
// of the level being worked on, in the canonical order of `hierarchy`;
// the stages move them and add to `stats`. Nothing is owned.
struct FitState {
  const SemiRegularHierarchy& hierarchy;
  const InputSurface& surface;
  const FitOptions& options;
  std::vector<Vec3>& positions;
  std::vector<SurfaceAnchor>& anchors;
  FitStats& stats;
};

// A vertex moved in the tangent plane by a distance d goes back onto the
// surface only if the surface (facing its way) is within this many d:
// otherwise the nearest such face is on another part and the vertex stays.
inline constexpr double kMaxProjectionRatio = 2.0;

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_FIT_STATE_H_
