// Surface fitting, least-squares stage: after the finest level is fitted
// (every vertex on the input surface), each vertex moves along its normal
// so that the remesh lies closer to the input in the least-squares sense.
// A remesh that interpolates the input is biased: on a convex part its flat
// triangles lie inside the surface, on a concave part outside; the
// distance energy of Hoppe, DeRose, Duchamp, McDonald, Stuetzle, "Mesh
// Optimization", SIGGRAPH 1993, with the vertex positions free, cuts that
// error at the same vertex count.
#ifndef MESHWAVE_REMESH_FIT_LEAST_SQUARES_H_
#define MESHWAVE_REMESH_FIT_LEAST_SQUARES_H_

#include <cstddef>

#include "remesh/fit_state.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {

struct LeastSquaresStats {
  size_t free_vertices = 0;   // inner vertices allowed to move
  size_t clamped = 0;         // offsets cut to the largest allowed
  size_t backed_off = 0;      // offsets reduced so that no face turns
  double mean_offset = 0;     // mean |t| over the free vertices
  size_t input_samples = 0;   // terms of input -> remesh, last round
  size_t remesh_samples = 0;  // terms of remesh -> input, last round
};

// Moves the finest vertices of state.hierarchy (rings: the finest level's
// vertex rings) to x_i + t_i n_i, n_i the area-weighted vertex normal
// before the stage, one scalar t_i per vertex (the tangential layout the
// fit chose stays; motion along the surface changes the distance little).
// options.least_squares_rounds Gauss-Newton rounds minimise
//   Σ_input samples w (dist to the remesh along its face normal)²
// + Σ_remesh samples w (dist to the input along the input's normal)²
// + smoothness Σ_edges ℓ² (t_i - t_j)²  + 1e-6 Σ_i area_i t_i²,
// so that both one-sided distances shrink (a symmetric distance takes the
// larger). Input samples: its vertices (weight area/12 per incident face)
// and face centroids (3/4 of the area), a rule exact for quadratics; remesh
// samples: its edge midpoints (a third of the two faces' areas), the
// midpoint rule. Each round projects the samples onto the current
// surfaces, solves the normal equations by conjugate gradients and clamps
// |t_i| to least_squares_max_offset times v's shortest edge; a vertex
// whose move turns one of its faces by more than 60° from the fitted
// face backs off. Vertices on a boundary (of the remesh or of the input)
// stay. Samples whose nearest point lies on a face turned away (another
// sheet) or of another component are left out. Deterministic for any
// number of threads.
LeastSquaresStats FitLeastSquares(const FitState& state,
                                  const VertexRings& rings);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_FIT_LEAST_SQUARES_H_
