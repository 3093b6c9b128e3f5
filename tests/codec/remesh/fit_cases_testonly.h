// Hand-made surface fits for the tests of the fitting stages
// (fit_projection.h, fit_relaxation.h, fold_repair.h): an input surface, a
// hierarchy over a small base mesh, and the positions and anchors a test
// sets up before running one stage on them.
#ifndef MESHWAVE_TESTS_CODEC_REMESH_FIT_CASES_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_REMESH_FIT_CASES_TESTONLY_H_

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "codec/test_meshes.h"
#include "meshwave/mesh.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "remesh/components.h"
#include "remesh/fit_state.h"
#include "remesh/input_surface.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::testing {

// A flat square [x0, x0 + size] x [y0, y0 + size] at z = 0 of n x n cells,
// each split into two triangles facing +z.
inline TriMesh FlatGrid(int n, double x0, double y0, double size) {
  TriMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.positions.emplace_back(x0 + size * i / n, y0 + size * j / n, 0.0);
    }
  }
  const auto at = [n](int i, int j) {
    return static_cast<uint32_t>(j * (n + 1) + i);
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return m;
}

// The unit sphere as an icosahedron subdivided `levels` times at edge
// midpoints, every vertex pushed out onto the sphere. Faces outward.
inline TriMesh IcoSphere(int levels) {
  TriMesh ico = Icosahedron();
  for (Vec3& p : ico.positions) p.normalize();
  if (levels == 0) return ico;
  Result<SemiRegularMesh> fine =
      Subdivide(ico, levels, SubdivisionScheme::kMidpoint);
  if (!fine.ok()) throw std::runtime_error(fine.status().ToString());
  TriMesh m = fine->Finest();
  for (Vec3& p : m.positions) p.normalize();
  return m;
}

// A regular hexagon of radius 1 around the origin at z = 0: the centre
// (vertex 0) and six rim vertices 1..6 counter-clockwise, six faces +z.
inline TriMesh HexagonFan() {
  TriMesh m;
  m.positions.emplace_back(0, 0, 0);
  for (int k = 0; k < 6; ++k) {
    const double a = std::numbers::pi * k / 3;
    m.positions.emplace_back(std::cos(a), std::sin(a), 0);
  }
  for (uint32_t k = 0; k < 6; ++k)
    m.faces.push_back({0, 1 + k, 1 + (k + 1) % 6});
  return m;
}

// A fit of `base` (levels deep) to `input`, one component, positions and
// anchors sized for the finest level: the base vertices where `base` has
// them, the others at zero until the test places them.
struct FitCase {
  FitCase(TriMesh input, const TriMesh& base, int levels) {
    remesh::Components components = remesh::LabelComponents(input);
    surface = std::make_unique<remesh::InputSurface>(std::move(input),
                                                     std::move(components));
    Result<std::shared_ptr<const SemiRegularHierarchy>> h =
        SemiRegularHierarchy::Build(
            static_cast<uint32_t>(base.positions.size()), base.faces, levels);
    if (!h.ok()) throw std::runtime_error(h.status().ToString());
    hierarchy = *h;
    positions.assign(hierarchy->vertex_count(levels), Vec3::Zero());
    std::copy(base.positions.begin(), base.positions.end(), positions.begin());
    anchors.assign(positions.size(), remesh::SurfaceAnchor{});
  }

  remesh::FitState state() {
    return {*hierarchy, *surface, options, positions, anchors, stats};
  }

  // The new vertex of level j + 1 that splits edge {a, b} of level j.
  uint32_t Splitting(int j, uint32_t a, uint32_t b) const {
    const auto& edges = hierarchy->edges(j);
    for (size_t k = 0; k < edges.size(); ++k) {
      if ((edges[k][0] == a && edges[k][1] == b) ||
          (edges[k][0] == b && edges[k][1] == a)) {
        return hierarchy->vertex_count(j) + static_cast<uint32_t>(k);
      }
    }
    throw std::invalid_argument("no such edge");
  }

  // Every new vertex of level j + 1 at the midpoint of its edge.
  void PlaceAtMidpoints(int j) {
    const auto& edges = hierarchy->edges(j);
    for (size_t k = 0; k < edges.size(); ++k) {
      positions[hierarchy->vertex_count(j) + k] =
          (positions[edges[k][0]] + positions[edges[k][1]]) / 2;
    }
  }

  // Anchors vertices [0, count) on the input face closest to them.
  void AnchorToClosest(uint32_t count) {
    for (uint32_t v = 0; v < count; ++v) {
      anchors[v].face =
          surface->ClosestAnywhere(positions[v], remesh::InputSurface::kNoFace)
              .face;
    }
  }

  VertexRings Rings(int level) const {
    Result<VertexRings> rings = VertexRings::Build(
        hierarchy->vertex_count(level), hierarchy->faces(level));
    if (!rings.ok()) throw std::runtime_error(rings.status().ToString());
    return std::move(*rings);
  }

  // Unnormalised normals of the faces of `level`.
  std::vector<Vec3> FaceNormals(int level) const {
    std::vector<Vec3> out;
    for (const Face& f : hierarchy->faces(level)) {
      out.push_back((positions[f[1]] - positions[f[0]])
                        .cross(positions[f[2]] - positions[f[0]]));
    }
    return out;
  }

  // Distance from p to the input surface.
  double OffSurface(const Vec3& p) const {
    return (surface->ClosestAnywhere(p, remesh::InputSurface::kNoFace).point -
            p)
        .norm();
  }

  std::unique_ptr<remesh::InputSurface> surface;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  remesh::FitOptions options;
  std::vector<Vec3> positions;
  std::vector<remesh::SurfaceAnchor> anchors;
  remesh::FitStats stats;
};

// Level 1 of HexagonFan fitted to the plane z = 0 (FlatGrid over
// [-2, 2]^2), every new vertex at its edge's midpoint, all 19 anchored:
// no fold, no sliver.
inline FitCase FlatHexagon() {
  FitCase fit(FlatGrid(8, -2, -2, 4), HexagonFan(), 1);
  fit.PlaceAtMidpoints(0);
  fit.AnchorToClosest(19);
  return fit;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_REMESH_FIT_CASES_TESTONLY_H_
