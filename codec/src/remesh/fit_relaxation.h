// Surface fitting, relaxation stage: evens out the new vertices of a level
// by tangential smoothing kept on the input surface, the relaxation step of
// the fit-relax-repair loop that MPEG's Video-based Dynamic Mesh Coding
// (V-DMC, ISO/IEC 23090-29) remeshing runs after each subdivision.
#ifndef MESHWAVE_REMESH_FIT_RELAXATION_H_
#define MESHWAVE_REMESH_FIT_RELAXATION_H_

#include "remesh/fit_state.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {

// One Jacobi round of relaxation of the new vertices of `level` (indices
// V_{level-1} and up): each inner one (not on the boundary of `rings`, the
// rings of that level, nor anchored on an input boundary loop) takes a step
// of options.relax_step toward its one-ring centroid in its tangent plane
// (the remesh's area-weighted vertex normal), then goes back onto the
// surface on the sheet it is on (input faces facing the way its anchor
// face does, within kMaxProjectionRatio times the step). It stays when no
// such point is found or that point is on the input's boundary. Vertices
// of coarser levels never move. Deterministic for any options.threads.
void Relax(const FitState& state, int level, const VertexRings& rings);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_FIT_RELAXATION_H_
