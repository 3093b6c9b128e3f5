// Area-weighted vertex normals: the remesher's fitting stages and the
// encoder's surface-weighted error share them.
#ifndef MESHWAVE_MESH_VERTEX_NORMALS_H_
#define MESHWAVE_MESH_VERTEX_NORMALS_H_

#include <cstddef>
#include <span>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave {

// Area-weighted unit normals of the first `count` vertices (zero for a
// vertex whose faces have no area). Faces may only use those vertices.
std::vector<Vec3> VertexNormals(const std::vector<Face>& faces,
                                std::span<const Vec3> positions, size_t count);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_VERTEX_NORMALS_H_
