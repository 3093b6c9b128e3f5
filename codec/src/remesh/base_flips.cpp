#include "remesh/base_flips.h"
#include "core/edge_key.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace meshwave::remesh {
namespace {

constexpr int kMaxPasses = 20;
constexpr double kMinGain = std::numbers::pi / 180;  // one degree
// Normals of the new faces against the old ones (and each other).
constexpr double kMinNormalCos = 0.5;

double MinAngle(const Vec3& a, const Vec3& b, const Vec3& c) {
  auto angle = [](const Vec3& at, const Vec3& p, const Vec3& q) {
    const Vec3 u = p - at, v = q - at;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

Vec3 Normal(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b - a).cross(c - a);
}

bool Agree(const Vec3& x, const Vec3& y) {
  const double nx = x.norm(), ny = y.norm();
  return nx > 0 && ny > 0 && x.dot(y) > kMinNormalCos * nx * ny;
}

}  // namespace

size_t FlipToImproveAngles(TriMesh& mesh) {
  const auto& p = mesh.positions;
  std::vector<uint32_t> faces_of_vertex(p.size(), 0);
  for (const Face& f : mesh.faces) {
    for (uint32_t v : f) ++faces_of_vertex[v];
  }
  size_t flips = 0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    // Undirected edge -> the faces holding it as (face, corner of edge).
    std::unordered_map<uint64_t, std::vector<std::pair<uint32_t, int>>> edges;
    edges.reserve(mesh.faces.size() * 2);
    for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
      for (int i = 0; i < 3; ++i) {
        edges[EdgeKey(mesh.faces[f][i], mesh.faces[f][(i + 1) % 3])].push_back(
            {f, i});
      }
    }
    std::vector<uint8_t> touched(mesh.faces.size(), 0);
    std::unordered_set<uint64_t> created;  // edges made in this pass
    size_t pass_flips = 0;
    for (const auto& [key, sides] : edges) {
      if (sides.size() != 2) continue;
      const auto [f, i] = sides[0];
      const auto [g, k] = sides[1];
      if (touched[f] || touched[g]) continue;
      // f = (a, b, c) with edge a -> b; g holds b -> a with apex d.
      const uint32_t a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      const uint32_t c = mesh.faces[f][(i + 2) % 3];
      const uint32_t d = mesh.faces[g][(k + 2) % 3];
      if (mesh.faces[g][k] != b || c == d) continue;
      if (faces_of_vertex[a] <= 3 || faces_of_vertex[b] <= 3) continue;
      if (edges.count(EdgeKey(c, d)) != 0 || created.count(EdgeKey(c, d)) != 0) {
        continue;
      }
      const double before =
          std::min(MinAngle(p[a], p[b], p[c]), MinAngle(p[b], p[a], p[d]));
      const double after =
          std::min(MinAngle(p[d], p[b], p[c]), MinAngle(p[c], p[a], p[d]));
      if (after < before + kMinGain) continue;
      const Vec3 old_f = Normal(p[a], p[b], p[c]);
      const Vec3 old_g = Normal(p[b], p[a], p[d]);
      const Vec3 new_f = Normal(p[d], p[b], p[c]);
      const Vec3 new_g = Normal(p[c], p[a], p[d]);
      const Vec3 old_sum = old_f + old_g;
      if (!Agree(new_f, new_g) || !Agree(new_f, old_sum) ||
          !Agree(new_g, old_sum)) {
        continue;
      }
      mesh.faces[f] = {d, b, c};
      mesh.faces[g] = {c, a, d};
      --faces_of_vertex[a];
      --faces_of_vertex[b];
      ++faces_of_vertex[c];
      ++faces_of_vertex[d];
      touched[f] = touched[g] = 1;
      created.insert(EdgeKey(c, d));
      ++pass_flips;
    }
    flips += pass_flips;
    if (pass_flips == 0) break;
  }
  return flips;
}

}  // namespace meshwave::remesh
