#include "mesh/vertex_normals.h"

#include <Eigen/Geometry>

namespace meshwave {

std::vector<Vec3> VertexNormals(const std::vector<Face>& faces,
                                std::span<const Vec3> positions, size_t count) {
  std::vector<Vec3> n(count, Vec3::Zero());
  for (const Face& f : faces) {
    const Vec3 c = (positions[f[1]] - positions[f[0]])
                       .cross(positions[f[2]] - positions[f[0]]);
    for (uint32_t v : f) n[v] += c;
  }
  for (Vec3& x : n) {
    const double length = x.norm();
    if (length > 0) x /= length;
  }
  return n;
}

}  // namespace meshwave
