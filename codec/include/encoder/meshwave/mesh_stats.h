// Describing a mesh: its bounding box and its combinatorial statistics
// (topology, boundaries, genus).
#ifndef MESHWAVE_MESH_STATS_H_
#define MESHWAVE_MESH_STATS_H_

#include <cstddef>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave {

struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  double Diagonal() const { return (max - min).norm(); }
};
// Bounding box of the positions (of all of them, referenced or not).
Aabb BoundingBox(const std::vector<Vec3>& positions);

// Combinatorial description of a mesh.
struct MeshStats {
  size_t vertices = 0;             // referenced by at least one face
  size_t unreferenced_vertices = 0;
  size_t faces = 0;
  size_t edges = 0;
  size_t boundary_edges = 0;
  size_t boundary_loops = 0;       // counted on manifold boundaries
  size_t components = 0;           // face-connected through shared vertices
  size_t non_manifold_edges = 0;   // more than two faces
  size_t non_manifold_vertices = 0;  // faces around it form several fans
  size_t inconsistently_oriented_edges = 0;  // both faces run it the same way
  bool manifold = false;
  bool closed = false;
  long euler_characteristic = 0;
  // Sum of the genera of the components; only meaningful when manifold.
  long genus = -1;
};
// Faces must index existing vertices. Linear time apart from tiny
// per-vertex sorts. Boundary loops are the connected components of the
// boundary-edge graph, which on a manifold boundary are exactly its cycles.
MeshStats ComputeStats(const TriMesh& mesh);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_STATS_H_
