// Finding input features a remesh misses: the input vertices farthest from
// it, for a second simplification that keeps them in the base.
#ifndef MESHWAVE_REMESH_MISSED_FEATURES_H_
#define MESHWAVE_REMESH_MISSED_FEATURES_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

struct MissedVertices {
  double max_distance = 0;         // of any input vertex to the remesh
  uint32_t farthest = 0;           // the vertex at that distance
  std::vector<uint32_t> vertices;  // chosen, farthest first
};

// Measures every referenced vertex of `input` against the surface of
// `remesh` (a BVH of its faces) and picks those farther than `threshold`,
// farthest first, skipping any within `spacing` of one already picked, at
// most `max_count` of them: one vertex per missed tip or corner.
MissedVertices FindMissedVertices(const TriMesh& input, const TriMesh& remesh,
                                  double threshold, double spacing,
                                  size_t max_count, int threads);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_MISSED_FEATURES_H_
