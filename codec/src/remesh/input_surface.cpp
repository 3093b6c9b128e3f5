#include "remesh/input_surface.h"

#include <Eigen/Geometry>

#include <utility>

namespace meshwave::remesh {
namespace {

// Closest-point projection accepts faces whose normal makes less than about
// 85° with the vertex normal: a sheet seen edge-on still counts (creases,
// rims of thin parts), the back of a thin part does not.
constexpr double kMinFacingCos = 0.08;

std::vector<Vec3> UnitNormals(const TriMesh& mesh) {
  std::vector<Vec3> out(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]])
                       .cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    const double length = n.norm();
    out[f] = length > 0 ? Vec3(n / length) : Vec3(Vec3::Zero());
  }
  return out;
}

}  // namespace

InputSurface::InputSurface(TriMesh mesh, Components components)
    : mesh_(std::move(mesh)),
      components_(std::move(components)),
      normals_(UnitNormals(mesh_)),
      bvh_(mesh_.positions, mesh_.faces),
      loops_(mesh_),
      diagonal_(BoundingBox(mesh_.positions).Diagonal()) {}

InputSurface::Projection InputSurface::AlongNormal(const Vec3& q,
                                                   const Vec3& n, double reach,
                                                   uint32_t component) const {
  const auto hit = bvh_.NearestLineHit(q, n, reach, [&](uint32_t f) {
    return components_.of_face[f] == component && normals_[f].dot(n) > 0;
  });
  return {hit.point, hit.face};
}

InputSurface::Projection InputSurface::Closest(const Vec3& q, const Vec3& n,
                                               uint32_t component,
                                               uint32_t hint) const {
  const double n_length = n.norm();
  const double min_dot = kMinFacingCos * n_length;
  const bool oriented = n_length > 0;
  const auto hit = bvh_.ClosestPointIf(q, hint, [&](uint32_t f) {
    return components_.of_face[f] == component &&
           (!oriented || normals_[f].dot(n) > min_dot);
  });
  return {hit.point, hit.face};
}

InputSurface::Projection InputSurface::ClosestAnywhere(const Vec3& q,
                                                       uint32_t hint) const {
  const auto hit = bvh_.ClosestPoint(q, hint);
  return {hit.point, hit.face};
}

}  // namespace meshwave::remesh
