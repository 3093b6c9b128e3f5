// Meshes built in code for the remeshing tests: irregular closed, open,
// genus-1 and broken inputs, small enough that a test remeshes in tens of
// milliseconds.
#ifndef MESHWAVE_TESTS_CODEC_REMESH_REMESH_MESHES_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_REMESH_REMESH_MESHES_TESTONLY_H_

#include <cmath>
#include <cstdint>
#include <numbers>

#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"

namespace meshwave::testing {

// A latitude-longitude sphere: `rings` bands of `segments` quads split into
// triangles, with fans at the poles, so valences range from 4 to
// `segments` (irregular, unlike a subdivided icosahedron). Outward facing.
inline TriMesh UvSphere(int rings, int segments, double radius = 1.0,
                        const Vec3& center = Vec3::Zero()) {
  TriMesh m;
  m.positions.push_back(center + Vec3(0, 0, radius));  // north pole
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.push_back(center +
                            radius * Vec3(std::sin(theta) * std::cos(phi),
                                          std::sin(theta) * std::sin(phi),
                                          std::cos(theta)));
    }
  }
  m.positions.push_back(center + Vec3(0, 0, -radius));  // south pole
  const auto at = [segments](int r, int s) {
    return static_cast<uint32_t>(1 + (r - 1) * segments + (s % segments));
  };
  const auto south = static_cast<uint32_t>(m.positions.size() - 1);
  for (int s = 0; s < segments; ++s) {
    m.faces.push_back({0, at(1, s), at(1, s + 1)});
    m.faces.push_back({south, at(rings - 1, s + 1), at(rings - 1, s)});
  }
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      m.faces.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      m.faces.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  }
  return m;
}

// A wavy square sheet of n x n cells, z = 0.1·sin(2x)·cos(3y), with a
// square hole of `hole` cells in the middle (0: none). Two boundary loops
// with a hole, one without. Faces +z.
inline TriMesh WavySheet(int n, int hole) {
  TriMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double x = 2.0 * i / n - 1, y = 2.0 * j / n - 1;
      m.positions.emplace_back(x, y, 0.1 * std::sin(2 * x) * std::cos(3 * y));
    }
  }
  const auto at = [n](int i, int j) {
    return static_cast<uint32_t>(j * (n + 1) + i);
  };
  const int lo = (n - hole) / 2, hi = lo + hole;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (hole > 0 && i >= lo && i < hi && j >= lo && j < hi) continue;
      // Alternate the diagonal so that valences vary.
      if ((i + j) % 2 == 0) {
        m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        m.faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        m.faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  }
  // Drop the vertices inside the hole that no face uses.
  CleanMesh(m);
  return m;
}

// A closed slab `thickness` thick, bent along a cylinder: the top sheet is
// the part of the cylinder of radius `radius` around the y axis through
// (0, 0, -radius) with |angle| <= `half_angle` and |y| <= half_width, the
// bottom sheet the same at radius - thickness, and four walls close it.
// n x n cells per sheet. Not oriented: run RepairManifold on it.
inline TriMesh ThinCurvedSlab(int n, double radius, double thickness,
                              double half_angle, double half_width) {
  TriMesh m;
  const auto at = [n](int sheet, int i, int j) {
    return static_cast<uint32_t>(sheet * (n + 1) * (n + 1) + j * (n + 1) + i);
  };
  for (int sheet = 0; sheet < 2; ++sheet) {
    const double r = sheet == 0 ? radius : radius - thickness;
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double angle = half_angle * (2.0 * i / n - 1);
        const double y = half_width * (2.0 * j / n - 1);
        m.positions.emplace_back(r * std::sin(angle), y,
                                 r * std::cos(angle) - radius);
      }
    }
  }
  for (int sheet = 0; sheet < 2; ++sheet) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const uint32_t a = at(sheet, i, j), b = at(sheet, i + 1, j),
                       c = at(sheet, i + 1, j + 1), d = at(sheet, i, j + 1);
        if (sheet == 0) {
          m.faces.push_back({a, b, c});
          m.faces.push_back({a, c, d});
        } else {
          m.faces.push_back({a, c, b});
          m.faces.push_back({a, d, c});
        }
      }
    }
  }
  // Walls: a strip of quads along each side, top to bottom.
  const auto wall = [&](uint32_t t0, uint32_t t1, uint32_t b0, uint32_t b1) {
    m.faces.push_back({t0, b0, b1});
    m.faces.push_back({t0, b1, t1});
  };
  for (int k = 0; k < n; ++k) {
    wall(at(0, k, 0), at(0, k + 1, 0), at(1, k, 0), at(1, k + 1, 0));
    wall(at(0, k + 1, n), at(0, k, n), at(1, k + 1, n), at(1, k, n));
    wall(at(0, 0, k + 1), at(0, 0, k), at(1, 0, k + 1), at(1, 0, k));
    wall(at(0, n, k), at(0, n, k + 1), at(1, n, k), at(1, n, k + 1));
  }
  return m;
}

// Appends `b` to `a` as a separate component.
inline TriMesh Combined(const TriMesh& a, const TriMesh& b) {
  TriMesh out = a;
  const auto offset = static_cast<uint32_t>(a.positions.size());
  out.positions.insert(out.positions.end(), b.positions.begin(),
                       b.positions.end());
  for (Face f : b.faces) {
    for (uint32_t& v : f) v += offset;
    out.faces.push_back(f);
  }
  return out;
}

// `mesh` moved by `offset`.
inline TriMesh Translated(TriMesh mesh, const Vec3& offset) {
  for (Vec3& p : mesh.positions) p += offset;
  return mesh;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_REMESH_REMESH_MESHES_TESTONLY_H_
