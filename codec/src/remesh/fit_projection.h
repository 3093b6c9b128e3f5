// Surface fitting, projection stage: puts the base vertices on the input
// surface, and then at every level the new (odd) vertices where their
// interpolated normal meets it, as normal meshes do (Guskov, Vidimče,
// Sweldens, Schröder, "Normal Meshes", SIGGRAPH 2000).
#ifndef MESHWAVE_REMESH_FIT_PROJECTION_H_
#define MESHWAVE_REMESH_FIT_PROJECTION_H_

#include <cstdint>
#include <vector>

#include "remesh/fit_state.h"
#include "remesh/input_surface.h"
#include "remesh/qem_simplifier.h"

namespace meshwave::remesh {

// Base positions and anchors: base vertices that kept an input vertex stay
// there (boundary ones learn their loop and arc length; those whose input
// vertex is set in `pinned`, if not empty, are pinned); the others move to
// the closest point of their component facing their normal.
void PlaceBaseVertices(const SimplifiedMesh& base, const InputSurface& surface,
                       const std::vector<uint8_t>& pinned,
                       std::vector<Vec3>& positions,
                       std::vector<SurfaceAnchor>& anchors);

// The odd vertices of level j + 1, whose predicted positions are in
// state.positions[V_j, V_{j+1}) (the vertices of level j placed and
// anchored), each moved onto the surface and anchored:
// - a new vertex on a boundary edge whose two ends lie on the same input
//   boundary loop goes to the arc-length midpoint of that edge's stretch
//   of the loop (stats.boundary_vertices);
// - any other goes to where the line along its interpolated normal (the
//   sum of its edge ends' area-weighted normals) first meets the input
//   facing the same way, within normal_reach edge lengths and about 3x the
//   distance to the nearest such surface point (stats.normal_hits);
// - failing that, to that nearest point, or to the closest point of its
//   component facing any way (stats.closest_fallbacks); a component
//   without faces leaves it at its prediction.
// Deterministic for any options.threads.
void PlaceNewVertices(const FitState& state, int j);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_FIT_PROJECTION_H_
