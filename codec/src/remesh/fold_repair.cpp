// Fold repair stage of surface fitting: untangling, then face-by-face fixes.
#include "remesh/fold_repair.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include "core/parallel_for.h"
#include "remesh/remesh_quality.h"
#include "remesh/ring_kernel.h"

namespace meshwave::remesh {
namespace {

// Sweeps of FixFolds over the faces still bad after untangling.
constexpr int kFixSweeps = 4;
// SlideOnLoop tries the points that cut the loop between a boundary
// vertex's neighbours into this many equal parts.
constexpr int kSlideSteps = 8;

}  // namespace

size_t FoldRepair::Run(int level, const VertexRings& rings) {
  UntangleLevel(level, rings);
  return FixFolds(level, rings);
}

// Untangling rounds at `level`: first the new vertices alone, then
// (second half of the rounds) every vertex of a bad face, coarser levels
// included. Returns the number of bad faces left.
size_t FoldRepair::UntangleLevel(int level, const VertexRings& rings) {
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
size_t FoldRepair::FixFolds(int level, const VertexRings& rings) {
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
int FoldRepair::FaceBadness(const Face& f) const {
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
std::pair<int, double> FoldRepair::RingBadness(uint32_t v,
                                               std::span<const uint32_t> ring,
                                               bool closed) const {
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
bool FoldRepair::TryFix(uint32_t v, const VertexRings& rings,
                        bool allow_equal) {
  if (rings.IsBoundary(v)) return SlideOnLoop(v, rings);
  if (anchors_[v].loop != BoundaryLoops::kNone) return false;
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
         {Vec3(start + d), RingKernelPoint(positions_, centroid, n, ring)}) {
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
bool FoldRepair::SlideOnLoop(uint32_t v, const VertexRings& rings) {
  const uint32_t loop = anchors_[v].loop;
  const auto ring = rings.Ring(v);
  if (loop == BoundaryLoops::kNone || ring.size() < 2) return false;
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
void FoldRepair::GrowMarks(const VertexRings& rings) {
  std::vector<uint8_t> grown = marked_;
  for (uint32_t v = 0; v < marked_.size(); ++v) {
    if (!marked_[v]) continue;
    for (uint32_t u : rings.Ring(v)) grown[u] = 1;
  }
  marked_ = std::move(grown);
}

// How bad the faces around inner vertex v would be with v at p, seen
// along `facing`: folded faces first, then the worst compactness.
std::pair<int, double> FoldRepair::LocalBadness(
    const Vec3& p, const Vec3& facing, std::span<const uint32_t> ring) const {
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
void FoldRepair::Untangle(int level, const VertexRings& rings,
                          bool move_pinned) {
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
      if (!marked_[v] || rings.IsBoundary(v) ||
          anchors_[v].loop != BoundaryLoops::kNone ||
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
           {Vec3(positions_[v] + d),
            RingKernelPoint(positions_, centroid, facing, ring)}) {
        const InputSurface::Projection p =
            surface_.Closest(q, facing, anchors_[v].component, face,
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

// Unit normals of the vertices of `level` from their faces that the last
// MarkBadFaces found good; zero for a vertex with none.
std::vector<Vec3> FoldRepair::ConsensusNormals(int level) const {
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
size_t FoldRepair::MarkBadFaces(int level, bool new_only) {
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

}  // namespace meshwave::remesh
