// FitLevels: predict, project, relax and untangle, one level at a time.
#include "remesh/surface_fitting.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <span>
#include <utility>

#include "meshwave/wavelet.h"
#include "remesh/parallel_for.h"
#include "remesh/remesh_quality.h"
#include "semiregular/vertex_rings.h"

namespace meshwave::remesh {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
// Untangling looks for a kernel point of rings of up to this many vertices
// (valences above it occur only in odd bases and use the first kMaxRing).
constexpr size_t kMaxRing = 64;
constexpr int kKernelIterations = 32;
// Height a face keeps over its ring edge after untangling, as a fraction
// of that edge: about a 6° corner at worst.
constexpr double kKernelMargin = 0.1;
// A vertex moved in the tangent plane by a distance d goes back onto the
// surface only if the surface (facing its way) is within this many d:
// otherwise the nearest such face is on another part and the vertex stays.
constexpr double kMaxProjectionRatio = 2.0;
// A new vertex moves along its normal at most kRayToNearestRatio times the
// distance to the nearest surface point facing its way, plus kRaySlack
// times the length of the edge it splits.
constexpr double kRayToNearestRatio = 3.0;
constexpr double kRaySlack = 0.05;
// Sweeps of FixFolds over the faces still bad after untangling.
constexpr int kFixSweeps = 4;
// SlideOnLoop tries the points that cut the loop between a boundary
// vertex's neighbours into this many equal parts.
constexpr int kSlideSteps = 8;

// Area-weighted unit normals of the first `count` vertices.
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
    for (int j = 1; j <= levels; ++j)
      total += static_cast<double>(h_.faces(j).size());
    for (int j = 0; j < levels; ++j) {
      transform.PredictLevel(
          j, std::span<Vec3>(positions_.data(), h_.vertex_count(j + 1)));
      PlaceNewVertices(j);
      MW_ASSIGN_OR_RETURN(
          VertexRings rings,
          VertexRings::Build(h_.vertex_count(j + 1), h_.faces(j + 1)));
      for (int r = 0; r < options_.relax_rounds; ++r) Relax(j + 1, rings);
      UntangleLevel(j + 1, rings);
      const size_t bad = FixFolds(j + 1, rings);
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
        // The closest point facing n bounds how far along the normal the
        // surface may be: a crossing much farther than that is another
        // part of the surface seen across a gap (an arm across an armpit).
        const InputSurface::Projection nearest =
            surface_.Closest(q, n, out.component, anchors_[a].face, reach);
        const double nearest_distance =
            nearest.found() ? (nearest.point - q).norm() : reach;
        const double ray_reach = std::min(
            reach, kRayToNearestRatio * nearest_distance +
                       kRaySlack * (positions_[a] - positions_[b]).norm());
        InputSurface::Projection p;
        if (length > 0) {
          p = surface_.AlongNormal(q, n, ray_reach, out.component);
        }
        if (p.found()) {
          ++my_hits;
        } else {
          ++my_fallbacks;
          p = nearest;
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

  // One Jacobi round of relaxation of the new inner vertices of `level`:
  // a step of relax_step toward the one-ring centroid in the tangent
  // plane, then back onto the surface, on the sheet the vertex is on (the
  // input face it is on decides which faces count as facing the right way).
  void Relax(int level, const VertexRings& rings) {
    const uint32_t first = h_.vertex_count(level - 1);
    const uint32_t count = h_.vertex_count(level);
    const std::vector<Vec3> normals =
        VertexNormals(h_.faces(level), positions_, count);
    std::vector<Vec3> next(count - first);
    std::vector<uint32_t> next_face(count - first);
    ParallelFor(count - first, options_.threads, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) {
        const uint32_t v = first + static_cast<uint32_t>(i);
        next[i] = positions_[v];
        next_face[i] = anchors_[v].face;
        if (rings.IsBoundary(v) || anchors_[v].loop != kNone) continue;
        const auto ring = rings.Ring(v);
        Vec3 centroid = Vec3::Zero();
        for (uint32_t u : ring) centroid += positions_[u];
        centroid /= static_cast<double>(ring.size());
        const Vec3& n = normals[v];
        Vec3 d = centroid - positions_[v];
        d -= d.dot(n) * n;
        const Vec3 q = positions_[v] + options_.relax_step * d;
        const uint32_t face = anchors_[v].face;
        const Vec3 facing =
            face != InputSurface::kNoFace ? surface_.FaceNormal(face) : n;
        const InputSurface::Projection p =
            surface_.Closest(q, facing, anchors_[v].component, face,
                             kMaxProjectionRatio * (q - positions_[v]).norm());
        // An inner vertex pushed onto the input's boundary would squeeze
        // the faces between it and the remesh boundary flat: stay.
        if (!p.found() || surface_.OnBoundary(p.point, p.face)) continue;
        next[i] = p.point;
        next_face[i] = p.face;
      }
    });
    for (uint32_t i = 0; i < count - first; ++i) {
      positions_[first + i] = next[i];
      anchors_[first + i].face = next_face[i];
    }
  }

  // Untangling rounds at `level`: first the new vertices alone, then
  // (second half of the rounds) every vertex of a bad face, coarser levels
  // included. Returns the number of bad faces left.
  size_t UntangleLevel(int level, const VertexRings& rings) {
    for (int r = 0; r < options_.repair_rounds; ++r) {
      const bool new_only = 2 * r < options_.repair_rounds;
      if (MarkBadFaces(level, new_only) == 0) return 0;
      // In the last quarter of rounds, when the vertices of bad faces alone
      // did not untangle them, their neighbours may make room too, and
      // pinned feature vertices may move.
      const bool last_quarter = 4 * r >= 3 * options_.repair_rounds;
      if (last_quarter) GrowMarks(rings);
      Untangle(level, rings, last_quarter);
    }
    return MarkBadFaces(level, false);
  }

  // The faces folds are judged on exactly, one vertex at a time: what
  // Untangle leaves (it judges moves by the remesh's own normals, in
  // parallel Jacobi rounds, on the surface only) is taken face by face, in
  // index order. Each inner vertex of a bad face (then, failing that, of
  // its neighbours) tries points toward the centroid and the kernel of its
  // ring, in the tangent planes of its good faces and of the input under
  // it, on the surface and off it (half-way and full); a move is kept only
  // if fewer of the vertex's faces are then flipped (IsFlipped, the test
  // the result is measured with) or degenerate. Sequential, so every move
  // is judged against the ring it will have, and deterministic. Returns
  // the number of bad faces left.
  size_t FixFolds(int level, const VertexRings& rings) {
    const auto& faces = h_.faces(level);
    size_t bad = MarkBadFaces(level, false);
    for (int sweep = 0; sweep < kFixSweeps && bad > 0; ++sweep) {
      std::vector<uint32_t> list;
      for (uint32_t f = 0; f < faces.size(); ++f) {
        if (bad_face_[f]) list.push_back(f);
      }
      for (uint32_t f : list) {
        if (FaceBadness(faces[f]) == 0) continue;
        bool fixed = false;
        for (uint32_t v : faces[f]) fixed = fixed || TryFix(v, rings);
        if (fixed) continue;
        // The ring of a corner may itself be folded (no kernel): its
        // neighbours move first when that leaves fewer bad faces around
        // them, or as many with a better worst face, then the corners
        // try again.
        for (uint32_t v : faces[f]) {
          for (uint32_t u : rings.Ring(v)) {
            if (!fixed && u != faces[f][0] && u != faces[f][1] &&
                u != faces[f][2]) {
              fixed = TryFix(u, rings, /*allow_equal=*/true) &&
                      FaceBadness(faces[f]) == 0;
            }
          }
        }
        for (uint32_t v : faces[f]) TryFix(v, rings);
      }
      bad = MarkBadFaces(level, false);
    }
    return bad;
  }

  // 1 when the face is flipped against the input or degenerate, else 0.
  int FaceBadness(const Face& f) const {
    const Vec3& a = positions_[f[0]];
    const Vec3& b = positions_[f[1]];
    const Vec3& c = positions_[f[2]];
    if (Compactness(a, b, c) < kDegenerateCompactness) return 1;
    return IsFlipped(surface_, a, b, c, anchors_[f[0]].component,
                     anchors_[f[0]].face)
               ? 1
               : 0;
  }

  // Bad faces around inner vertex v (closed ring) and minus the worst
  // compactness, for comparing positions of v.
  std::pair<int, double> RingBadness(uint32_t v, std::span<const uint32_t> ring,
                                     bool closed = true) const {
    int count = 0;
    double worst = 1;
    const size_t faces = closed ? ring.size() : ring.size() - 1;
    for (size_t i = 0; i < faces; ++i) {
      const Face f = {v, ring[i], ring[(i + 1) % ring.size()]};
      count += FaceBadness(f);
      worst = std::min(worst, Compactness(positions_[f[0]], positions_[f[1]],
                                          positions_[f[2]]));
    }
    return {count, -worst};
  }

  // Moves inner vertex v to the best of its candidate points if that leaves
  // fewer bad faces around it (or, with allow_equal, as many but with a
  // better worst face). Returns whether it moved.
  bool TryFix(uint32_t v, const VertexRings& rings, bool allow_equal = false) {
    if (rings.IsBoundary(v)) return SlideOnLoop(v, rings);
    if (anchors_[v].loop != kNone) return false;
    const auto ring = rings.Ring(v);
    const auto now = RingBadness(v, ring);
    if (now.first == 0 && !allow_equal) return false;
    const Vec3 start = positions_[v];
    const uint32_t face = anchors_[v].face;
    // Normals: of the good faces around v, and of the input under v.
    Vec3 good = Vec3::Zero();
    for (size_t i = 0; i < ring.size(); ++i) {
      const Face f = {v, ring[i], ring[(i + 1) % ring.size()]};
      if (FaceBadness(f)) continue;
      good += (positions_[f[1]] - start).cross(positions_[f[2]] - start);
    }
    Vec3 centroid = Vec3::Zero();
    for (uint32_t u : ring) centroid += positions_[u];
    centroid /= static_cast<double>(ring.size());
    std::array<Vec3, 2> normals = {Vec3::Zero(), Vec3::Zero()};
    if (good.norm() > 0) normals[0] = good.normalized();
    if (face != InputSurface::kNoFace) normals[1] = surface_.FaceNormal(face);
    auto best = now;
    Vec3 best_point = start;
    uint32_t best_face = face;
    const auto consider = [&](const Vec3& p, uint32_t p_face) {
      positions_[v] = p;
      const auto badness = RingBadness(v, ring);
      positions_[v] = start;
      if (badness < best) {
        best = badness;
        best_point = p;
        best_face = p_face;
      }
    };
    for (const Vec3& n : normals) {
      if (!(n.norm() > 0)) continue;
      Vec3 d = centroid - start;
      d -= d.dot(n) * n;
      for (const Vec3& target :
           {Vec3(start + d), KernelPoint(centroid, n, ring)}) {
        for (const double t : {1.0, 0.5}) {
          const Vec3 q = start + t * (target - start);
          const InputSurface::Projection p =
              surface_.Closest(q, n, anchors_[v].component, face,
                               kMaxProjectionRatio * (q - start).norm());
          if (p.found() && !surface_.OnBoundary(p.point, p.face)) {
            consider(p.point, p.face);
          }
          consider(q, p.found() ? p.face : face);
        }
      }
    }
    // Then toward each ring vertex: a face across a sharp rim may need its
    // corner moved along the rim rather than toward the ring's middle.
    if (best.first > 0) {
      const uint32_t component = anchors_[v].component;
      for (uint32_t u : ring) {
        for (const double t : {0.5, 0.25}) {
          const Vec3 q = start + t * (positions_[u] - start);
          const InputSurface::Projection p =
              surface_.Closest(q, Vec3::Zero(), component, face,
                               kMaxProjectionRatio * (q - start).norm());
          if (p.found() && !surface_.OnBoundary(p.point, p.face)) {
            consider(p.point, p.face);
          }
          consider(q, p.found() ? p.face : face);
        }
      }
    }
    const bool better =
        best.first < now.first || (allow_equal && best.first == now.first &&
                                   best.second < now.second - 1e-3);
    if (!better || best_point == start) return false;
    positions_[v] = best_point;
    anchors_[v].face = best_face;
    ++stats_.repair_moves;
    return true;
  }

  // A boundary vertex on an input boundary loop, between two neighbours on
  // the same loop, tries other points of the loop between them (a face
  // folded over a jagged boundary can only unfold along it). Moves if that
  // leaves fewer bad faces around it.
  bool SlideOnLoop(uint32_t v, const VertexRings& rings) {
    const uint32_t loop = anchors_[v].loop;
    const auto ring = rings.Ring(v);
    if (loop == kNone || ring.size() < 2) return false;
    uint32_t x = ring.front(), y = ring.back();
    if (anchors_[x].loop != loop || anchors_[y].loop != loop) return false;
    const BoundaryLoops& loops = surface_.loops();
    const double length = loops.Length(loop);
    const auto forward = [&](double from, double to) {
      return std::fmod(std::fmod(to - from, length) + length, length);
    };
    if (forward(anchors_[x].s, anchors_[v].s) >
        forward(anchors_[x].s, anchors_[y].s)) {
      std::swap(x, y);
    }
    const double from = anchors_[x].s;
    const double span = forward(from, anchors_[y].s);
    const auto now = RingBadness(v, ring, false);
    if (now.first == 0 || !(span > 0)) return false;
    const Vec3 start = positions_[v];
    auto best = now;
    double best_s = anchors_[v].s;
    BoundaryLoops::Point best_point{start, anchors_[v].face};
    for (int k = 1; k < kSlideSteps; ++k) {
      const double s = from + span * k / kSlideSteps;
      const BoundaryLoops::Point p = loops.At(loop, s);
      positions_[v] = p.position;
      const auto badness = RingBadness(v, ring, false);
      positions_[v] = start;
      if (badness < best) {
        best = badness;
        best_s = s;
        best_point = p;
      }
    }
    if (!(best.first < now.first)) return false;
    positions_[v] = best_point.position;
    anchors_[v].face = best_point.face;
    anchors_[v].s = std::fmod(best_s, length);
    ++stats_.repair_moves;
    return true;
  }

  // Marks the one-ring of every marked vertex too.
  void GrowMarks(const VertexRings& rings) {
    std::vector<uint8_t> grown = marked_;
    for (uint32_t v = 0; v < marked_.size(); ++v) {
      if (!marked_[v]) continue;
      for (uint32_t u : rings.Ring(v)) grown[u] = 1;
    }
    marked_ = std::move(grown);
  }

  // How bad the faces around inner vertex v would be with v at p, seen
  // along `facing`: folded faces first, then the worst compactness.
  std::pair<int, double> LocalBadness(const Vec3& p, const Vec3& facing,
                                      std::span<const uint32_t> ring) const {
    int folded = 0;
    double worst = 1;
    for (size_t i = 0; i < ring.size(); ++i) {
      const Vec3& b = positions_[ring[i]];
      const Vec3& c = positions_[ring[(i + 1) % ring.size()]];
      if ((b - p).cross(c - p).dot(facing) <= 0) ++folded;
      worst = std::min(worst, Compactness(p, b, c));
    }
    return {folded, -worst};
  }

  // One Jacobi round of untangling: every marked inner vertex (of any
  // level; pinned ones only with move_pinned) tries the ring centroid and a
  // kernel point of its ring, both in the tangent plane of its good faces
  // (ConsensusNormals: the remesh's own normal is unreliable inside a fold, and
  // the input face it is on may be on the far side of a part thinner than an
  // edge), projected onto the surface facing that way; it takes whichever
  // leaves its faces least bad, or stays.
  void Untangle(int level, const VertexRings& rings, bool move_pinned) {
    const uint32_t count = h_.vertex_count(level);
    const std::vector<Vec3> normals = ConsensusNormals(level);
    std::vector<Vec3> next(positions_.begin(), positions_.begin() + count);
    std::vector<uint32_t> next_face(count);
    for (uint32_t v = 0; v < count; ++v) next_face[v] = anchors_[v].face;
    std::atomic<size_t> moves{0};
    ParallelFor(count, options_.threads, [&](size_t begin, size_t end) {
      size_t my_moves = 0;
      for (size_t i = begin; i < end; ++i) {
        const auto v = static_cast<uint32_t>(i);
        if (!marked_[v] || rings.IsBoundary(v) || anchors_[v].loop != kNone ||
            (anchors_[v].pinned && !move_pinned)) {
          continue;
        }
        const uint32_t face = anchors_[v].face;
        Vec3 facing = normals[v];
        if (!(facing.norm() > 0) && face != InputSurface::kNoFace) {
          facing = surface_.FaceNormal(face);
        }
        if (!(facing.norm() > 0)) continue;
        const auto ring = rings.Ring(v);
        Vec3 centroid = Vec3::Zero();
        for (uint32_t u : ring) centroid += positions_[u];
        centroid /= static_cast<double>(ring.size());
        Vec3 d = centroid - positions_[v];
        d -= d.dot(facing) * facing;
        auto best = LocalBadness(positions_[v], facing, ring);
        for (const Vec3& q :
             {Vec3(positions_[v] + d), KernelPoint(centroid, facing, ring)}) {
          const InputSurface::Projection p = surface_.Closest(
              q, facing, anchors_[v].component, face,
              kMaxProjectionRatio * (q - positions_[v]).norm());
          if (!p.found() || surface_.OnBoundary(p.point, p.face)) continue;
          const auto badness = LocalBadness(p.point, facing, ring);
          if (badness < best) {
            best = badness;
            next[v] = p.point;
            next_face[v] = p.face;
          }
        }
        if (next[v] != positions_[v]) ++my_moves;
      }
      moves += my_moves;
    });
    for (uint32_t v = 0; v < count; ++v) {
      positions_[v] = next[v];
      anchors_[v].face = next_face[v];
    }
    stats_.repair_moves += moves;
  }

  // A point of the tangent plane (normal n, through `start`) from which
  // every face to two consecutive ring vertices is positively oriented with
  // some height to spare: the kernel of the star-shaped ring polygon,
  // found by cyclic projection onto the half-planes of its edges (POCS).
  // The ring centroid, the relaxation target, stays in a fold when the
  // ring polygon is not convex (a reflex corner of the boundary); the
  // kernel does not. When the kernel is empty the iteration ends near it.
  Vec3 KernelPoint(const Vec3& start, const Vec3& n,
                   std::span<const uint32_t> ring) const {
    const Vec3 t1 = n.unitOrthogonal();
    const Vec3 t2 = n.cross(t1);
    std::array<Eigen::Vector2d, kMaxRing> r;
    const size_t k = std::min(ring.size(), kMaxRing);
    for (size_t i = 0; i < k; ++i) {
      const Vec3 d = positions_[ring[i]] - start;
      r[i] = {d.dot(t1), d.dot(t2)};
    }
    Eigen::Vector2d x = Eigen::Vector2d::Zero();
    for (int iteration = 0; iteration < kKernelIterations; ++iteration) {
      bool inside = true;
      for (size_t i = 0; i < k; ++i) {
        const Eigen::Vector2d& a = r[i];
        const Eigen::Vector2d& b = r[(i + 1) % k];
        const Eigen::Vector2d e = b - a;
        const double length = e.norm();
        if (!(length > 0)) continue;
        // Left of a -> b by at least kKernelMargin · |ab|.
        const Eigen::Vector2d inward(-e.y() / length, e.x() / length);
        const double height = inward.dot(x - a);
        const double want = kKernelMargin * length;
        if (height < want) {
          x += (want - height) * inward;
          inside = false;
        }
      }
      if (inside) break;
    }
    return start + x.x() * t1 + x.y() * t2;
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
        // Shortcut: a face within 60° of the input normal at each of its
        // corners is not turned over; the full test queries the surface.
        const Vec3 n = (b - a).cross(c - a);
        const double length = n.norm();
        bool agrees = length > 0;
        for (uint32_t v : f) {
          agrees = agrees && anchors_[v].face != InputSurface::kNoFace &&
                   n.dot(surface_.FaceNormal(anchors_[v].face)) > 0.5 * length;
        }
        if (agrees) continue;
        bad_face[i] = IsFlipped(surface_, a, b, c, anchors_[f[0]].component,
                                anchors_[f[0]].face);
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
