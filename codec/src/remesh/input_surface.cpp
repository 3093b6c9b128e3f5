#include "remesh/input_surface.h"
#include "core/edge_key.h"
#include "meshwave/mesh_stats.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace meshwave::remesh {
namespace {

// Closest-point projection accepts faces whose normal makes less than about
// 85° with the vertex normal: a sheet seen edge-on still counts (creases,
// rims of thin parts), the back of a thin part does not.
constexpr double kMinProjectionFacingCos = 0.08;

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

// Bit i of entry f is set when edge i (corner i -> i+1) of face f has no
// twin, i.e. lies on the boundary.
std::vector<uint8_t> BoundaryEdgeBits(const TriMesh& mesh) {
  std::vector<std::pair<uint64_t, uint32_t>> directed;
  directed.reserve(mesh.faces.size() * 3);
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t i = 0; i < 3; ++i) {
      const uint32_t a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      directed.push_back({DirectedEdgeKey(a, b), 3 * f + i});
    }
  }
  std::sort(directed.begin(), directed.end());
  std::vector<uint8_t> bits(mesh.faces.size(), 0);
  for (const auto& [key, corner] : directed) {
    const uint64_t twin = ReversedEdgeKey(key);
    auto it =
        std::lower_bound(directed.begin(), directed.end(), twin,
                         [](const auto& e, uint64_t k) { return e.first < k; });
    if (it != directed.end() && it->first == twin) continue;
    bits[corner / 3] |= static_cast<uint8_t>(1u << (corner % 3));
  }
  return bits;
}

}  // namespace

InputSurface::InputSurface(TriMesh mesh, Components components)
    : mesh_(std::move(mesh)),
      components_(std::move(components)),
      normals_(UnitNormals(mesh_)),
      boundary_edges_(BoundaryEdgeBits(mesh_)),
      bvh_(mesh_.positions, mesh_.faces),
      loops_(mesh_),
      diagonal_(BoundingBox(mesh_.positions).Diagonal()) {}

InputSurface::Projection InputSurface::AlongNormal(const Vec3& q, const Vec3& n,
                                                   double reach,
                                                   uint32_t component) const {
  const auto hit = bvh_.NearestLineHit(q, n, reach, [&](uint32_t f) {
    return components_.of_face[f] == component && normals_[f].dot(n) > 0;
  });
  return {hit.point, hit.face};
}

InputSurface::Projection InputSurface::Closest(const Vec3& q, const Vec3& n,
                                               uint32_t component,
                                               uint32_t hint,
                                               double max_distance) const {
  const double n_length = n.norm();
  const double min_dot = kMinProjectionFacingCos * n_length;
  const bool oriented = n_length > 0;
  const auto hit = bvh_.ClosestPointIf(
      q, hint,
      [&](uint32_t f) {
        return components_.of_face[f] == component &&
               (!oriented || normals_[f].dot(n) > min_dot);
      },
      max_distance * max_distance);
  return {hit.point, hit.face};
}

InputSurface::Projection InputSurface::ClosestWithin(const Vec3& q,
                                                     const Vec3& n,
                                                     double min_dot,
                                                     uint32_t component,
                                                     uint32_t hint) const {
  const bool oriented = n.squaredNorm() > 0;
  const auto hit = bvh_.ClosestPointIf(
      q, hint,
      [&](uint32_t f) {
        return components_.of_face[f] == component &&
               (!oriented || normals_[f].dot(n) > min_dot);
      },
      std::numeric_limits<double>::infinity());
  return {hit.point, hit.face};
}

bool InputSurface::OnBoundary(const Vec3& point, uint32_t face) const {
  const uint8_t bits = boundary_edges_[face];
  if (bits == 0) return false;
  const Face& t = mesh_.faces[face];
  for (int i = 0; i < 3; ++i) {
    if (!(bits & (1u << i))) continue;
    const Vec3& a = mesh_.positions[t[i]];
    const Vec3& b = mesh_.positions[t[(i + 1) % 3]];
    const Vec3 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double s =
        length2 > 0 ? std::clamp((point - a).dot(ab) / length2, 0.0, 1.0) : 0;
    if ((a + s * ab - point).squaredNorm() <= 1e-18 * length2) return true;
  }
  return false;
}

InputSurface::Projection InputSurface::ClosestAnywhere(const Vec3& q,
                                                       uint32_t hint) const {
  const auto hit = bvh_.ClosestPoint(q, hint);
  return {hit.point, hit.face};
}

}  // namespace meshwave::remesh
