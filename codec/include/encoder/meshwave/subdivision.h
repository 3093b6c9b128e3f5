// Making semi-regular meshes (meshwave/semiregular.h) from triangle
// meshes: refining a base by subdivision, renumbering a base, and
// recovering the subdivision hierarchy of a flat mesh.
#ifndef MESHWAVE_SUBDIVISION_H_
#define MESHWAVE_SUBDIVISION_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/stream_limits.h"

namespace meshwave {

enum class SubdivisionScheme { kMidpoint, kLoop, kButterfly };
Result<SubdivisionScheme> ParseSubdivisionScheme(const std::string& name);
const char* SubdivisionSchemeName(SubdivisionScheme scheme);

// Refines a manifold base mesh `levels` times. Midpoint and butterfly
// (Zorin's modified butterfly) interpolate the base vertices; Loop also moves
// them (approximating). Every vertex of `base` must be referenced.
Result<SemiRegularMesh> Subdivide(const TriMesh& base, int levels,
                                  SubdivisionScheme scheme);

// The same mesh over a reordered base: base vertex v becomes new_of_old[v]
// and the base faces (in new indices, any order and rotation, same
// orientation) are new_base_faces. Finer vertices are renumbered by the
// canonical rules. Fails if the faces are not the base mesh's. When
// `old_of_new` is given, it receives each new vertex's index in `mesh` (for
// per-vertex attributes to follow).
Result<SemiRegularMesh> RenumberBase(const SemiRegularMesh& mesh,
                                     const std::vector<uint32_t>& new_of_old,
                                     std::vector<Face> new_base_faces,
                                     std::vector<uint32_t>* old_of_new = nullptr);

struct DetectOptions {
  int max_levels = kMaxStreamLevels;  // stop after this many levels even if more exist
};

struct DetectedSemiRegular {
  SemiRegularMesh mesh;
  // canonical vertex index -> index in the mesh given to DetectSemiRegular.
  std::vector<uint32_t> original_index;
  // Why detection stopped at this level (for messages).
  std::string stop_reason;
};

// Recovers the subdivision hierarchy of a flat mesh, whatever its vertex and
// face order, and renumbers it canonically. The mesh must be clean (every
// vertex referenced, no duplicate faces). Returns kNotSemiRegular, with the
// reason, when not even one level of 1-to-4 splitting can be undone; meshes
// with several components are handled when every component has the same
// number of levels.
Result<DetectedSemiRegular> DetectSemiRegular(const TriMesh& mesh,
                                              const DetectOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_SUBDIVISION_H_
