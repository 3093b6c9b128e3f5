// Separating vertices that would share a position in the written file: a
// mesh reader that merges equal positions (CleanMesh, `meshwave info`) would
// otherwise glue sheets together that the remesh keeps apart (copies of a
// split non-manifold vertex, two components touching at a point).
#ifndef MESHWAVE_REMESH_COINCIDENT_VERTICES_H_
#define MESHWAVE_REMESH_COINCIDENT_VERTICES_H_

#include <cstddef>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

// Moves every vertex whose float32-rounded position equals that of a vertex
// before it 1 % of the way toward the centroid of its faces, until all
// float32 positions differ. Returns how many moves were made.
size_t SeparateCoincidentVertices(std::vector<Vec3>& positions,
                                  const std::vector<Face>& faces);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_COINCIDENT_VERTICES_H_
