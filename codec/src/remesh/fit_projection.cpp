// Projection stage of surface fitting: base and new vertices onto the input.
#include "remesh/fit_projection.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>

#include "core/parallel_for.h"

namespace meshwave::remesh {
namespace {

// A new vertex moves along its normal at most kRayToNearestRatio times the
// distance to the nearest surface point facing its way, plus kRaySlack
// times the length of the edge it splits.
constexpr double kRayToNearestRatio = 3.0;
constexpr double kRaySlack = 0.05;

}  // namespace

void PlaceBaseVertices(const SimplifiedMesh& base, const InputSurface& surface,
                       const std::vector<uint8_t>& pinned,
                       std::vector<Vec3>& positions,
                       std::vector<SurfaceAnchor>& anchors) {
  const size_t n = base.mesh.positions.size();
  const std::vector<Vec3> normals =
      VertexNormals(base.mesh.faces, base.mesh.positions, n);
  positions.assign(base.mesh.positions.begin(), base.mesh.positions.end());
  anchors.assign(n, SurfaceAnchor{});
  for (size_t v = 0; v < n; ++v) {
    SurfaceAnchor& a = anchors[v];
    a.component = base.component[v];
    const uint32_t source = base.source_vertex[v];
    if (source != SimplifiedMesh::kNone) {
      const BoundaryLoops::Location where = surface.loops().Locate(source);
      a.loop = where.loop;
      a.s = where.s;
      a.pinned = source < pinned.size() && pinned[source] != 0;
      positions[v] = surface.mesh().positions[source];
      // The input vertex is on the surface; find a face of it.
      a.face = surface
                   .Closest(positions[v], Vec3::Zero(), a.component,
                            InputSurface::kNoFace)
                   .face;
      continue;
    }
    InputSurface::Projection p = surface.Closest(
        positions[v], normals[v], a.component, InputSurface::kNoFace);
    if (!p.found()) {
      p = surface.Closest(positions[v], Vec3::Zero(), a.component,
                          InputSurface::kNoFace);
    }
    if (p.found()) {
      positions[v] = p.point;
      a.face = p.face;
    }
  }
}

void PlaceNewVertices(const FitState& state, int j) {
  const SemiRegularHierarchy& h = state.hierarchy;
  const InputSurface& surface = state.surface;
  std::vector<Vec3>& positions = state.positions;
  std::vector<SurfaceAnchor>& anchors = state.anchors;
  const uint32_t vj = h.vertex_count(j);
  const auto& edges = h.edges(j);
  const auto& edge_faces = h.edge_faces(j);
  const auto& face_edges = h.face_edges(j);
  const auto& faces = h.faces(j);
  const std::vector<Vec3> normals = VertexNormals(faces, positions, vj);
  std::atomic<size_t> hits{0}, fallbacks{0}, boundary{0};
  ParallelFor(
      edges.size(), state.options.threads, [&](size_t begin, size_t end) {
        size_t my_hits = 0, my_fallbacks = 0, my_boundary = 0;
        for (size_t k = begin; k < end; ++k) {
          const uint32_t m = vj + static_cast<uint32_t>(k);
          const uint32_t a = edges[k][0], b = edges[k][1];
          SurfaceAnchor& out = anchors[m];
          out = SurfaceAnchor{};
          out.component = anchors[a].component;
          if (edge_faces[k][1] == SemiRegularHierarchy::kNone) {
            // A boundary edge runs from corner i to i+1 of its only face.
            const uint32_t f = edge_faces[k][0];
            int i = 0;
            while (face_edges[f][i] != k) ++i;
            const uint32_t from = faces[f][i], to = faces[f][(i + 1) % 3];
            const uint32_t loop = anchors[from].loop;
            if (loop != BoundaryLoops::kNone && anchors[to].loop == loop) {
              const BoundaryLoops& loops = surface.loops();
              out.loop = loop;
              out.s = loops.Midway(loop, anchors[from].s, anchors[to].s);
              const BoundaryLoops::Point p = loops.At(loop, out.s);
              positions[m] = p.position;
              out.face = p.face;
              ++my_boundary;
              continue;
            }
          }
          Vec3 n = normals[a] + normals[b];
          if (!(n.norm() > 1e-12)) {
            n = Vec3::Zero();
            for (uint32_t f : edge_faces[k]) {
              if (f == SemiRegularHierarchy::kNone) continue;
              const Face& t = faces[f];
              n += (positions[t[1]] - positions[t[0]])
                       .cross(positions[t[2]] - positions[t[0]]);
            }
          }
          const double length = n.norm();
          if (length > 0) n /= length;
          const Vec3 q = positions[m];
          const double reach =
              state.options.normal_reach * (positions[a] - positions[b]).norm();
          // The closest point facing n bounds how far along the normal the
          // surface may be: a crossing much farther than that is another
          // part of the surface seen across a gap (an arm across an armpit).
          const InputSurface::Projection nearest =
              surface.Closest(q, n, out.component, anchors[a].face, reach);
          const double nearest_distance =
              nearest.found() ? (nearest.point - q).norm() : reach;
          const double ray_reach = std::min(
              reach, kRayToNearestRatio * nearest_distance +
                         kRaySlack * (positions[a] - positions[b]).norm());
          InputSurface::Projection p;
          if (length > 0) {
            p = surface.AlongNormal(q, n, ray_reach, out.component);
          }
          if (p.found()) {
            ++my_hits;
          } else {
            ++my_fallbacks;
            p = nearest;
            if (!p.found()) {
              p = surface.Closest(q, Vec3::Zero(), out.component,
                                  anchors[a].face);
            }
          }
          if (p.found()) {
            positions[m] = p.point;
            out.face = p.face;
          } else {
            out.face = anchors[a].face;  // a component without faces: keep q
          }
        }
        hits += my_hits;
        fallbacks += my_fallbacks;
        boundary += my_boundary;
      });
  state.stats.normal_hits += hits;
  state.stats.closest_fallbacks += fallbacks;
  state.stats.boundary_vertices += boundary;
}

}  // namespace meshwave::remesh
