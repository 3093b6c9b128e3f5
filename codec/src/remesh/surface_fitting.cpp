// FitLevels: predict, project, relax and untangle, one level at a time.
#include "remesh/surface_fitting.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <span>
#include <utility>
#include <cstdio>
#include <cstdlib>

#include "meshwave/wavelet.h"
#include "remesh/parallel_for.h"
#include "remesh/remesh_quality.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
double Compactness(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() +
                     (a - c).squaredNorm();
  if (!(sum > 0)) return 0;
  return 2 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sum;
}

// Area-weighted unit normals of the first `count` vertices.
std::vector<Vec3> VertexNormals(const std::vector<Face>& faces,
                                std::span<const Vec3> positions,
                                size_t count) {
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

class Fitter {
 public:
  Fitter(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
         const InputSurface& surface, const FitOptions& options,
         std::vector<Vec3>& positions, std::vector<SurfaceAnchor>& anchors,
         FitStats& stats)
      : hierarchy_(std::move(hierarchy)),
        h_(*hierarchy_),
        surface_(surface),
        options_(options),
        positions_(positions),
        anchors_(anchors),
        stats_(stats) {}

  Status Run() {
    TransformSettings settings;
    settings.predictor = Predictor::kButterfly;
    settings.update = UpdateWeights::kNone;
    settings.frames = FrameMode::kGlobal;
    MW_ASSIGN_OR_RETURN(WaveletTransform transform,
                        WaveletTransform::Create(hierarchy_, settings));
    const int levels = h_.levels();
    positions_.resize(h_.vertex_count(levels));
    anchors_.resize(h_.vertex_count(levels));
    // Work grows 4x per level; the fractions reported follow the faces.
    double total = 0, done = 0;
    for (int j = 1; j <= levels; ++j) total += static_cast<double>(h_.faces(j).size());
    if (getenv("MW_DEBUG")) {
      size_t b0 = 0;
      for (const Face& f : h_.faces(0)) {
        Vec3 in = Vec3::Zero();
        for (uint32_t v : f) if (anchors_[v].face != InputSurface::kNoFace) in += surface_.FaceNormal(anchors_[v].face);
        if ((positions_[f[1]]-positions_[f[0]]).cross(positions_[f[2]]-positions_[f[0]]).dot(in) <= 0) ++b0;
      }
      fprintf(stderr, "level 0: bad %zu\n", b0);
    }
    for (int j = 0; j < levels; ++j) {
      transform.PredictLevel(
          j, std::span<Vec3>(positions_.data(), h_.vertex_count(j + 1)));
      PlaceNewVertices(j);
      MW_ASSIGN_OR_RETURN(
          VertexRings rings,
          VertexRings::Build(h_.vertex_count(j + 1), h_.faces(j + 1)));
      for (int r = 0; r < options_.relax_rounds; ++r) Relax(j + 1, rings, false);
      // Untangling: first the new vertices alone, then (second half of the
      // rounds) every vertex of a bad face, coarser levels included.
      size_t bad = 0;
      if (getenv("MW_DEBUG")) fprintf(stderr, "level %d: bad after relax %zu\n", j+1, MarkBadFaces(j+1, false));
      const int repair_rounds = getenv("MW_REPAIR") ? atoi(getenv("MW_REPAIR")) : options_.repair_rounds;
      for (int r = 0; r < repair_rounds; ++r) {
        bad = MarkBadFaces(j + 1, 2 * r < options_.repair_rounds);
        if (bad == 0) break;
        Relax(j + 1, rings, true);
      }
      bad = MarkBadFaces(j + 1, false);
      if (getenv("MW_DEBUG")) fprintf(stderr, "level %d: bad after repair %zu\n", j+1, bad);
      if (j + 1 == levels) stats_.unrepaired_faces = bad;
      done += static_cast<double>(h_.faces(j + 1).size());
      if (options_.progress) options_.progress(j + 1, done / total);
    }
    return Status::Ok();
  }

 private:
  // Odd vertices of level j+1, predicted in place, moved onto the surface.
  void PlaceNewVertices(int j) {
    const uint32_t vj = h_.vertex_count(j);
    const auto& edges = h_.edges(j);
    const auto& edge_faces = h_.edge_faces(j);
    const auto& face_edges = h_.face_edges(j);
    const auto& faces = h_.faces(j);
    const std::vector<Vec3> normals = VertexNormals(faces, positions_, vj);
    std::atomic<size_t> hits{0}, fallbacks{0}, boundary{0};
    ParallelFor(edges.size(), options_.threads, [&](size_t begin, size_t end) {
      size_t my_hits = 0, my_fallbacks = 0, my_boundary = 0;
      for (size_t k = begin; k < end; ++k) {
        const uint32_t m = vj + static_cast<uint32_t>(k);
        const uint32_t a = edges[k][0], b = edges[k][1];
        SurfaceAnchor& out = anchors_[m];
        out = SurfaceAnchor{};
        out.component = anchors_[a].component;
        if (edge_faces[k][1] == SemiRegularHierarchy::kNone) {
          // A boundary edge runs from corner i to i+1 of its only face.
          const uint32_t f = edge_faces[k][0];
          int i = 0;
          while (face_edges[f][i] != k) ++i;
          const uint32_t from = faces[f][i], to = faces[f][(i + 1) % 3];
          const uint32_t loop = anchors_[from].loop;
          if (loop != kNone && anchors_[to].loop == loop) {
            const BoundaryLoops& loops = surface_.loops();
            out.loop = loop;
            out.s = loops.Midway(loop, anchors_[from].s, anchors_[to].s);
            const BoundaryLoops::Point p = loops.At(loop, out.s);
            positions_[m] = p.position;
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
            n += (positions_[t[1]] - positions_[t[0]])
                     .cross(positions_[t[2]] - positions_[t[0]]);
          }
        }
        const double length = n.norm();
        if (length > 0) n /= length;
        const Vec3 q = positions_[m];
        const double reach =
            options_.normal_reach * (positions_[a] - positions_[b]).norm();
        InputSurface::Projection p;
        if (length > 0) p = surface_.AlongNormal(q, n, reach, out.component);
        if (p.found()) {
          ++my_hits;
        } else {
          ++my_fallbacks;
          p = surface_.Closest(q, n, out.component, anchors_[a].face);
          if (!p.found()) {
            p = surface_.Closest(q, Vec3::Zero(), out.component,
                                 anchors_[a].face);
          }
        }
        if (p.found()) {
          positions_[m] = p.point;
          out.face = p.face;
        } else {
          out.face = anchors_[a].face;  // a component without faces: keep q
        }
      }
      hits += my_hits;
      fallbacks += my_fallbacks;
      boundary += my_boundary;
    });
    stats_.normal_hits += hits;
    stats_.closest_fallbacks += fallbacks;
    stats_.boundary_vertices += boundary;
  }

  // One Jacobi round of relaxation at `level`: a step toward the one-ring
  // centroid in the tangent plane, then back onto the surface, on the sheet
  // the vertex is on. Normally the new inner vertices take a step of
  // relax_step; when untangling, every marked inner vertex (of any level)
  // takes the full step, in the tangent plane of the input face it is on
  // (the remesh's own normal is unreliable inside a fold).
  void Relax(int level, const VertexRings& rings, bool untangle) {
    const uint32_t first = untangle ? 0 : h_.vertex_count(level - 1);
    const uint32_t count = h_.vertex_count(level);
    const std::vector<Vec3> normals =
        untangle ? ConsensusNormals(level)
                 : VertexNormals(h_.faces(level), positions_, count);
    std::vector<Vec3> next(count - first);
    std::vector<uint32_t> next_face(count - first);
    const double step = untangle ? 1.0 : options_.relax_step;
    std::atomic<size_t> moves{0};
    ParallelFor(count - first, options_.threads, [&](size_t begin, size_t end) {
      size_t my_moves = 0;
      for (size_t i = begin; i < end; ++i) {
        const uint32_t v = first + static_cast<uint32_t>(i);
        next[i] = positions_[v];
        next_face[i] = anchors_[v].face;
        if (rings.IsBoundary(v) || anchors_[v].loop != kNone) continue;
        if (untangle && !marked_[v]) continue;
        Vec3 centroid = Vec3::Zero();
        const auto ring = rings.Ring(v);
        for (uint32_t u : ring) centroid += positions_[u];
        centroid /= static_cast<double>(ring.size());
        // Facing: when relaxing, the input face the vertex is on (it is on
        // the right sheet); when untangling, the orientation of the
        // vertex's faces that are not bad, which brings back a vertex that
        // went to the far side of a part thinner than an edge.
        const uint32_t face = anchors_[v].face;
        Vec3 facing = untangle || face == InputSurface::kNoFace
                          ? normals[v]
                          : surface_.FaceNormal(face);
        if (!(facing.norm() > 0) && face != InputSurface::kNoFace) {
          facing = surface_.FaceNormal(face);
        }
        const Vec3& n = untangle ? facing : normals[v];
        Vec3 d = centroid - positions_[v];
        d -= d.dot(n) * n;
        const Vec3 q = positions_[v] + step * d;
        const InputSurface::Projection p =
            surface_.Closest(q, facing, anchors_[v].component, face);
        if (!p.found()) continue;
        next[i] = p.point;
        next_face[i] = p.face;
        ++my_moves;
      }
      moves += my_moves;
    });
    for (uint32_t i = 0; i < count - first; ++i) {
      if (untangle && getenv("MW_DEBUG") && (positions_[first+i]-next[i]).norm() > 0.003*surface_.diagonal()) {
        int lv = 0; while (first+i >= h_.vertex_count(lv)) ++lv;
        fprintf(stderr, "  untangle L%d: v%u (level %d) moved %.4f diag to (%.4f %.4f %.4f)\n", level, first+i, lv, (positions_[first+i]-next[i]).norm()/surface_.diagonal(), next[i].x(), next[i].y(), next[i].z());
      }
      positions_[first + i] = next[i];
      anchors_[first + i].face = next_face[i];
    }
    if (untangle) stats_.repair_moves += moves;
  }

  // Unit normals of the vertices of `level` from their faces that the last
  // MarkBadFaces found good; zero for a vertex with none.
  std::vector<Vec3> ConsensusNormals(int level) const {
    const auto& faces = h_.faces(level);
    std::vector<Vec3> n(h_.vertex_count(level), Vec3::Zero());
    for (size_t i = 0; i < faces.size(); ++i) {
      if (bad_face_[i]) continue;
      const Face& f = faces[i];
      const Vec3 c = (positions_[f[1]] - positions_[f[0]])
                         .cross(positions_[f[2]] - positions_[f[0]]);
      for (uint32_t v : f) n[v] += c;
    }
    for (Vec3& x : n) {
      const double length = x.norm();
      if (length > 0) x /= length;
    }
    return n;
  }

  // Marks the vertices of folded or degenerate faces of `level`;
  // returns the number of such faces. Folded: the face normal opposes the
  // input normal at the point of its component closest to its centroid
  // (the test MeasureQuality applies to the result). With `new_only`,
  // vertices of coarser levels are not marked.
  size_t MarkBadFaces(int level, bool new_only) {
    const uint32_t first = new_only ? h_.vertex_count(level - 1) : 0;
    marked_.assign(h_.vertex_count(level), 0);
    const auto& faces = h_.faces(level);
    std::vector<uint8_t> bad_face(faces.size(), 0);
    ParallelFor(faces.size(), options_.threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const Face& f = faces[i];
        const Vec3& a = positions_[f[0]];
        const Vec3& b = positions_[f[1]];
        const Vec3& c = positions_[f[2]];
        if (Compactness(a, b, c) < kDegenerateCompactness) {
          bad_face[i] = 1;
          continue;
        }
        const Vec3 n = (b - a).cross(c - a);
        const InputSurface::Projection p =
            surface_.Closest((a + b + c) / 3, Vec3::Zero(),
                             anchors_[f[0]].component, anchors_[f[0]].face);
        if (p.found() && n.dot(surface_.FaceNormal(p.face)) > 0) continue;
        bad_face[i] = 1;
      }
    });
    size_t bad = 0;
    bad_face_ = bad_face;
    for (size_t i = 0; i < faces.size(); ++i) {
      if (!bad_face[i]) continue;
      ++bad;
      for (uint32_t v : faces[i]) {
        if (v >= first) marked_[v] = 1;
      }
    }
    return bad;
  }

  std::shared_ptr<const SemiRegularHierarchy> hierarchy_;
  const SemiRegularHierarchy& h_;
  const InputSurface& surface_;
  const FitOptions& options_;
  std::vector<Vec3>& positions_;
  std::vector<SurfaceAnchor>& anchors_;
  FitStats& stats_;
  std::vector<uint8_t> marked_;
  std::vector<uint8_t> bad_face_;  // of the level last checked
};

}  // namespace

void PlaceBaseVertices(const SimplifiedMesh& base, const InputSurface& surface,
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
      positions[v] = surface.mesh().positions[source];
      // The input vertex is on the surface; find a face of it.
      a.face = surface.Closest(positions[v], Vec3::Zero(), a.component,
                               InputSurface::kNoFace).face;
      continue;
    }
    InputSurface::Projection p =
        surface.Closest(positions[v], normals[v], a.component,
                        InputSurface::kNoFace);
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

Status FitLevels(std::shared_ptr<const SemiRegularHierarchy> hierarchy,
                 const InputSurface& surface, const FitOptions& options,
                 std::vector<Vec3>& positions,
                 std::vector<SurfaceAnchor>& anchors, FitStats* stats) {
  FitStats local;
  Fitter fitter(std::move(hierarchy), surface, options, positions, anchors,
                stats != nullptr ? *stats : local);
  return fitter.Run();
}

}  // namespace meshwave::remesh
