// Surface fitting: places the vertices of every level of a semi-regular
// hierarchy on the input surface, level by level, as normal meshes do
// (Guskov, Vidimče, Sweldens, Schröder, "Normal Meshes", SIGGRAPH 2000),
// with the fit-relax-repair loop of the remeshing in MPEG's Video-based
// Dynamic Mesh Coding (V-DMC, ISO/IEC 23090-29). The stages are in
// fit_projection.h, fit_relaxation.h and fold_repair.h; this runs them.
#ifndef MESHWAVE_REMESH_SURFACE_FITTING_H_
#define MESHWAVE_REMESH_SURFACE_FITTING_H_

#include <memory>
#include <vector>

#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "remesh/fit_state.h"
#include "remesh/input_surface.h"

namespace meshwave::remesh {

// Fits levels 1..J. On entry `positions` and `anchors` hold the V_0 base
// vertices (from PlaceBaseVertices, fit_projection.h); on return all V_J,
// in the canonical order of `hierarchy`. For each level:
// 1. butterfly prediction of the new vertices, then PlaceNewVertices: each
//    moves to where its interpolated normal meets the input facing the
//    same way, within normal_reach edge lengths and 3x the distance to the
//    nearest such surface point (else to that nearest point); new boundary
//    vertices go to the arc-length midpoint of their edge on the input
//    boundary loop;
// 2. relax_rounds of Relax, tangential relaxation of the new inner
//    vertices, each step re-projected onto the sheet the vertex is on;
// 3. FoldRepair: untangling of folded faces (IsFlipped) and degenerate
//    ones: their vertices (first only the new ones, then any) try the ring
//    centroid and a kernel point of their ring and keep the better, for
//    repair_rounds; then (FixFolds) the faces still bad, one at a time in
//    index order: a corner moves (toward its ring's centroid or kernel, or
//    toward one ring neighbour; on the surface or, failing that, just off
//    it) when fewer of its faces are then bad by the exact test; a corner
//    on an input boundary loop slides along the loop.
// Deterministic: the same input gives the same result for any thread count.
Status FitLevels(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
                 const InputSurface& surface, const FitOptions& options,
                 std::vector<Vec3>& positions,
                 std::vector<SurfaceAnchor>& anchors, FitStats* stats);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_SURFACE_FITTING_H_
