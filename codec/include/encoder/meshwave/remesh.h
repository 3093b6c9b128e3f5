// Remeshing: turns any triangle mesh into a semi-regular mesh that follows
// its surface closely, the input the wavelet codec needs.
//
// Pipeline: clean (CleanMesh) -> repair into an oriented manifold (split
// non-manifold edges and vertices, orient each component) -> simplify by
// quadric-error edge collapses to a base mesh with the same topology and
// boundaries (every component its own base patches) -> subdivide J times,
// placing every new vertex on the input surface (along the interpolated
// normal, else the closest point; boundary vertices along the input
// boundary), with tangential relaxation and untangling of folded faces
// after each level. When the result misses an input vertex by more than
// 0.5 % of the diagonal (a thin tip simplification let go), up to two more
// attempts keep the missed vertices in the base; the best result is kept.
// Design and measured figures: docs/REMESH_RESULTS.md.
#ifndef MESHWAVE_REMESH_H_
#define MESHWAVE_REMESH_H_

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

struct RemeshOptions {
  // Levels J of 1-to-4 subdivision; -1 chooses from the input size (3 or 4
  // for typical scans, 2 for small meshes, 5 only past about 2 M vertices).
  int levels = -1;
  // About how many base faces, N; -1 chooses N so that the finest level has
  // about as many vertices as the cleaned input. Shared between components
  // by simplification error (cheapest collapses first, anywhere); every
  // component keeps at least 16 faces (all of its faces when it has
  // fewer). Parts that cannot shrink without folding can leave the base
  // larger than N (a warning says so).
  int base_faces = -1;
  // Tangential relaxation rounds after each level (0 turns it off).
  int relax_rounds = 3;
  // Least-squares rounds after the finest level's fit (0 turns them off):
  // every finest vertex moves along its normal so that the remesh lies
  // closer to the input than an interpolating one can (Hoppe et al.,
  // "Mesh Optimization", 1993; codec/src/remesh/fit_least_squares.h).
  int least_squares_rounds = 1;
  // Worker threads (1 = the calling thread only; 0 = the machine's cores):
  // the surface's set-up runs beside the simplification, the quadrics and
  // the fitting's per-vertex steps on all of them. The result is the same
  // for any number.
  int threads = 0;
  // Components with no area at all (every face degenerate) are always
  // dropped; with this set, components of fewer than `tiny_component_faces`
  // faces are dropped too. Either way a warning says how many.
  bool drop_tiny_components = false;
  int tiny_component_faces = 8;
  // Progress: stage name ("repair", "simplify", "fit", "refine", "check",
  // "done") and the fraction of the whole run done, from 0 to 1, never
  // decreasing. Called on the calling thread; may be empty.
  std::function<void(std::string_view stage, double fraction)> progress;
};

// What remeshing produced and found. Counts describe the input after
// cleaning and repair unless they say otherwise.
struct RemeshResult {
  SemiRegularMesh mesh;

  // Input.
  CleanReport cleaning;
  size_t input_vertices = 0;  // referenced, after cleaning
  size_t input_faces = 0;
  size_t components = 0;          // remeshed
  size_t dropped_components = 0;  // with no area, or tiny when asked
  size_t dropped_faces = 0;
  size_t tiny_components = 0;  // kept, each as its own small base
  size_t non_manifold_edges = 0;
  size_t non_manifold_vertices = 0;
  size_t split_vertex_copies = 0;
  size_t reoriented_faces = 0;

  // Result.
  int levels = 0;
  size_t target_base_faces = 0;  // N asked for or chosen
  size_t base_vertices = 0;
  size_t base_faces = 0;
  size_t finest_vertices = 0;
  size_t finest_faces = 0;

  // Quality of the finest level against the repaired input.
  size_t flipped_faces = 0;     // normal opposing the input's under it
  size_t degenerate_faces = 0;  // no area to speak of (min angle < 0.005°)
  double min_angle_degrees = 0;
  // Fitting: new vertices placed along the normal, at the closest point,
  // on a boundary loop.
  size_t normal_hits = 0;
  size_t closest_fallbacks = 0;
  size_t boundary_vertices = 0;
  // Input vertices kept in the base by a second attempt because the first
  // result missed them (tips, corners); 0 when one attempt was enough.
  size_t locked_features = 0;

  double seconds = 0;  // wall time of Remesh
  std::vector<std::pair<std::string, double>> stage_seconds;
  // Things a user should know (dropped or tiny components, base larger
  // than asked, ...), one sentence each.
  std::vector<std::string> warnings;
};

// Remeshes `input` (any triangle mesh; it is cleaned and repaired first, the
// argument is not changed). Safe on untrusted meshes: non-finite
// coordinates, out-of-range indices, or nothing usable left after cleaning
// (no faces, or only faces without area) give kInvalidArgument naming what
// is wrong and where; levels outside [1, 8] or a hierarchy larger than 2^27
// finest faces give kInvalidArgument. Time is about linear in the input and
// output sizes (1 M input triangles: about 15 s and 600 MB on two cores;
// up to three times that when retries run). Deterministic: the same input
// and options give the same mesh for any thread count.
Result<RemeshResult> Remesh(const TriMesh& input,
                            const RemeshOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_REMESH_H_
