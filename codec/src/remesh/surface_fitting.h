// Surface fitting: places the vertices of every level of a semi-regular
// hierarchy on the input surface, level by level, as normal meshes do
// (Guskov et al. 2000) with the fit-relax-repair loop of V-DMC
// (MPEG V-DMC, ISO/IEC 23090-29).
#ifndef MESHWAVE_REMESH_SURFACE_FITTING_H_
#define MESHWAVE_REMESH_SURFACE_FITTING_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "remesh/input_surface.h"
#include "remesh/qem_simplifier.h"

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

// Base positions and anchors: base vertices that kept an input vertex stay
// there (boundary ones learn their loop and arc length; those whose input
// vertex is set in `pinned`, if not empty, are pinned); the others move to
// the closest point of their component facing their normal.
void PlaceBaseVertices(const SimplifiedMesh& base, const InputSurface& surface,
                       const std::vector<uint8_t>& pinned,
                       std::vector<Vec3>& positions,
                       std::vector<SurfaceAnchor>& anchors);

// Fits levels 1..J. On entry `positions` and `anchors` hold the V_0 base
// vertices (from PlaceBaseVertices); on return all V_J, in the canonical
// order of `hierarchy`. For each level:
// 1. butterfly prediction of the new vertices; each then moves to where its
//    interpolated normal meets the input facing the same way, within
//    normal_reach edge lengths and 3x the distance to the nearest such
//    surface point (else to that nearest point); new boundary vertices go
//    to the arc-length midpoint of their edge on the input boundary loop;
// 2. relax_rounds of tangential relaxation of the new inner vertices, each
//    step re-projected onto the sheet the vertex is on;
// 3. untangling of folded faces (IsFlipped) and degenerate ones: their
//    vertices (first only the new ones, then any) try the ring centroid and
//    a kernel point of their ring and keep the better, for repair_rounds;
// 4. FixFolds: the faces still flipped (IsFlipped) or degenerate, one at a
//    time in index order: a corner moves (toward its ring's centroid or
//    kernel, or toward one ring neighbour; on the surface or, failing
//    that, just off it) when fewer of its faces are then bad by the exact
//    test; a corner on an input boundary loop slides along the loop.
// Deterministic: the same input gives the same result for any thread count.
Status FitLevels(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
                 const InputSurface& surface, const FitOptions& options,
                 std::vector<Vec3>& positions,
                 std::vector<SurfaceAnchor>& anchors, FitStats* stats);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_SURFACE_FITTING_H_
