// Meshes built in code for the metrics tests: flat grid patches and
// icospheres, whose exact distances are known in closed form.
#ifndef MESHWAVE_TESTS_CODEC_METRICS_TEST_MESHES_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_METRICS_TEST_MESHES_TESTONLY_H_

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::testing {

// An n × n grid of squares covering [x0, x0 + size] × [y0, y0 + size] at
// height z, each square split into two triangles facing +z.
inline TriMesh GridPatch(int n, double x0, double y0, double size,
                         double z = 0) {
  TriMesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.positions.emplace_back(x0 + size * i / n, y0 + size * j / n, z);
    }
  }
  const auto at = [n](int i, int j) {
    return static_cast<uint32_t>(j * (n + 1) + i);
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

inline TriMesh Translated(TriMesh mesh, const Vec3& offset) {
  for (Vec3& p : mesh.positions) p += offset;
  return mesh;
}

// The regular icosahedron inscribed in the unit sphere, refined `levels`
// times by 1-to-4 splits with the new vertices pushed onto the sphere.
inline TriMesh Icosphere(int levels) {
  TriMesh mesh;
  const double phi = (1 + std::sqrt(5.0)) / 2;
  // Cyclic permutations of (0, ±1, ±phi).
  for (int axis = 0; axis < 3; ++axis) {
    for (const double s1 : {-1.0, 1.0}) {
      for (const double s2 : {-phi, phi}) {
        Vec3 p;
        p[axis] = 0;
        p[(axis + 1) % 3] = s1;
        p[(axis + 2) % 3] = s2;
        mesh.positions.push_back(p.normalized());
      }
    }
  }
  // The faces are the triples of mutually nearest vertices (edge length 2
  // before normalising), oriented outward.
  double edge = std::numeric_limits<double>::infinity();
  for (uint32_t x = 1; x < 12; ++x) {
    edge = std::min(edge, (mesh.positions[0] - mesh.positions[x]).norm());
  }
  const auto adjacent = [&](uint32_t x, uint32_t y) {
    return std::abs((mesh.positions[x] - mesh.positions[y]).norm() - edge) <
           1e-9;
  };
  for (uint32_t a = 0; a < 12; ++a) {
    for (uint32_t b = a + 1; b < 12; ++b) {
      for (uint32_t c = b + 1; c < 12; ++c) {
        if (!adjacent(a, b) || !adjacent(b, c) || !adjacent(a, c)) continue;
        const Vec3& pa = mesh.positions[a];
        const Vec3 normal =
            (mesh.positions[b] - pa).cross(mesh.positions[c] - pa);
        if (normal.dot(pa) > 0) {
          mesh.faces.push_back({a, b, c});
        } else {
          mesh.faces.push_back({a, c, b});
        }
      }
    }
  }
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    const auto midpoint = [&](uint32_t x, uint32_t y) {
      const std::pair<uint32_t, uint32_t> key{std::min(x, y), std::max(x, y)};
      auto [it, inserted] = midpoints.try_emplace(
          key, static_cast<uint32_t>(mesh.positions.size()));
      if (inserted) {
        mesh.positions.push_back(
            (mesh.positions[x] + mesh.positions[y]).normalized());
      }
      return it->second;
    };
    std::vector<Face> faces;
    for (const Face& f : mesh.faces) {
      const uint32_t ab = midpoint(f[0], f[1]);
      const uint32_t bc = midpoint(f[1], f[2]);
      const uint32_t ca = midpoint(f[2], f[0]);
      faces.push_back({f[0], ab, ca});
      faces.push_back({ab, f[1], bc});
      faces.push_back({ca, bc, f[2]});
      faces.push_back({ab, bc, ca});
    }
    mesh.faces = std::move(faces);
  }
  return mesh;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_METRICS_TEST_MESHES_TESTONLY_H_
