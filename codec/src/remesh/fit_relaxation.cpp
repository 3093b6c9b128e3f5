// Relaxation stage of surface fitting: tangential smoothing on the surface.
#include "remesh/fit_relaxation.h"

#include "core/parallel_for.h"

namespace meshwave::remesh {

void Relax(const FitState& state, int level, const VertexRings& rings) {
  const SemiRegularHierarchy& h = state.hierarchy;
  const InputSurface& surface = state.surface;
  std::vector<Vec3>& positions = state.positions;
  std::vector<SurfaceAnchor>& anchors = state.anchors;
  const uint32_t first = h.vertex_count(level - 1);
  const uint32_t count = h.vertex_count(level);
  const std::vector<Vec3> normals =
      VertexNormals(h.faces(level), positions, count);
  std::vector<Vec3> next(count - first);
  std::vector<uint32_t> next_face(count - first);
  ParallelFor(
      count - first, state.options.threads, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          const uint32_t v = first + static_cast<uint32_t>(i);
          next[i] = positions[v];
          next_face[i] = anchors[v].face;
          if (rings.IsBoundary(v) || anchors[v].loop != BoundaryLoops::kNone) {
            continue;
          }
          const auto ring = rings.Ring(v);
          Vec3 centroid = Vec3::Zero();
          for (uint32_t u : ring) centroid += positions[u];
          centroid /= static_cast<double>(ring.size());
          const Vec3& n = normals[v];
          Vec3 d = centroid - positions[v];
          d -= d.dot(n) * n;
          const Vec3 q = positions[v] + state.options.relax_step * d;
          const uint32_t face = anchors[v].face;
          const Vec3 facing =
              face != InputSurface::kNoFace ? surface.FaceNormal(face) : n;
          const InputSurface::Projection p =
              surface.Closest(q, facing, anchors[v].component, face,
                              kMaxProjectionRatio * (q - positions[v]).norm());
          // An inner vertex pushed onto the input's boundary would squeeze
          // the faces between it and the remesh boundary flat: stay.
          if (!p.found() || surface.OnBoundary(p.point, p.face)) continue;
          next[i] = p.point;
          next_face[i] = p.face;
        }
      });
  for (uint32_t i = 0; i < count - first; ++i) {
    positions[first + i] = next[i];
    anchors[first + i].face = next_face[i];
  }
}

}  // namespace meshwave::remesh
