// SimplifyByEdgeCollapse: a lazy priority queue of edges keyed by quadric
// error; stale entries are recognised by per-vertex stamps.
#include "remesh/qem_simplifier.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>

#include "core/edge_key.h"
#include "core/parallel_for.h"
#include "remesh/quadric.h"
#include "remesh/remesh_quality.h"

namespace meshwave::remesh {
namespace {

constexpr uint32_t kNone = SimplifiedMesh::kNone;
// Boundary planes weigh this many times the squared edge length: enough
// that collapsing along a curved boundary costs like the face planes of a
// sharp crease, so holes keep their shape.
constexpr double kBoundaryWeight = 10.0;
// Edge-length term: cost += kLengthWeight · |uv|^4 (same units as an
// area-weighted squared distance). Breaks ties in flat regions in favour of
// short edges, so the base has even triangles there; in curved regions the
// quadric dominates (the term equals the quadric when a face spans about 5°
// of curvature).
constexpr double kLengthWeight = 1e-3;
// A face may turn by at most acos(0.25) ≈ 75° in one collapse.
constexpr double kMinNormalCos = 0.25;
// Compactness 4√3·area / Σ edge² (1 for an equilateral triangle). A
// collapse may not make the worst triangle around it worse and below
// kMinQuality (about a 2° corner), and doing so below kGoodQuality is put
// off until nothing else is left: a cap or needle in the base folds once
// subdivision moves its new vertices onto a curved surface.
constexpr double kMinQuality = 0.05;
constexpr double kGoodQuality = 0.3;
// Every vertex carries the summed (area-weighted) input normal of the
// region merged into it. A collapse that makes a face whose corners'
// normals differ by more than 90° (unless the faces around were already
// that bad, as at sharp creases) is put off until no other collapse is
// left: such a face spans a bend (the cross-section of a thin tube reduced
// to a triangle, a fin seen from both sides), and subdividing and
// projecting it folds or skips the part. Measured on feline.ply: with such
// collapses allowed the Hausdorff distance is 1.7 % of the diagonal, put
// off 0.4 %; refusing them outright stalls ogre.obj at twice the planned
// base (claws and teeth keep 100+ faces each).
constexpr double kMinCornerNormalCos = 0.0;
// A face made by a collapse must face within acos(0.2) ≈ 78° of the mean
// input normal of its corners.
constexpr double kMinCollapseFacingCos = 0.2;
// Inner vertices of valence 3 make cones: after subdivision and projection
// their corner faces fold easily, so making one is put off.
constexpr size_t kMinInnerValence = 4;

bool Contains(const Face& f, uint32_t v) {
  return f[0] == v || f[1] == v || f[2] == v;
}

uint32_t ThirdCorner(const Face& f, uint32_t a, uint32_t b) {
  for (uint32_t x : f) {
    if (x != a && x != b) return x;
  }
  return kNone;
}

class Simplifier {
 public:
  Simplifier(const TriMesh& mesh, const Components& components,
             const SimplifyOptions& options)
      : options_(options),
        positions_(mesh.positions),
        faces_(mesh.faces),
        face_alive_(mesh.faces.size(), 1),
        vertex_faces_(mesh.positions.size()),
        quadrics_(mesh.positions.size()),
        normal_sums_(mesh.positions.size(), Vec3::Zero()),
        boundary_(mesh.positions.size(), 0),
        stamp_(mesh.positions.size(), 0),
        source_(mesh.positions.size()),
        component_(components.of_vertex),
        component_faces_(components.count, 0),
        max_edge_squared_(options.max_edge_length * options.max_edge_length) {
    for (uint32_t v = 0; v < source_.size(); ++v) source_[v] = v;
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      for (uint32_t v : faces_[f]) vertex_faces_[v].push_back(f);
      ++component_faces_[components.of_face[f]];
    }
  }

  SimplifiedMesh Run() {
    const std::vector<std::pair<uint64_t, uint32_t>> edges = InitQuadrics();
    size_t faces = faces_.size();
    const size_t planned =
        faces > options_.target_faces ? (faces - options_.target_faces) / 2 : 0;
    std::vector<Entry> storage;
    storage.reserve(edges.size() + 8 * planned);
    if (planned > 0) {
      storage.resize(edges.size());
      ParallelFor(edges.size(), options_.threads, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
          const uint64_t key = edges[i].first;
          storage[i] = MakeEntry(static_cast<uint32_t>(key >> 32),
                                 static_cast<uint32_t>(key), false);
        }
      });
    }
    // Heapified at once (linear) rather than pushed one by one.
    queue_ = std::priority_queue<Entry, std::vector<Entry>, std::greater<>>(
        std::greater<>(), std::move(storage));
    size_t done = 0;
    const size_t report_every = std::max<size_t>(planned / 100, 1000);
    // The collapses on this thread, `beside` (if any) on another.
    const auto collapse = [&] { CollapseAll(faces, planned, report_every, done); };
    if (options_.beside) {
      ParallelInvoke(options_.threads, collapse, options_.beside);
    } else {
      collapse();
    }
    return Compact(done);
  }

 private:
  void CollapseAll(size_t& faces, size_t planned, size_t report_every, size_t& done) {
    while (!queue_.empty() && faces > options_.target_faces) {
      const Entry e = queue_.top();
      queue_.pop();
      if (e.tag != Tag(e.u, e.v, e.late())) continue;
      const uint32_t c = component_[e.u];
      if (component_faces_[c] <= MinFaces(c)) continue;
      const Candidate cand = Evaluate(e.u, e.v);
      if (std::isinf(cand.cost)) continue;
      // keep == 0: u's position, so u survives; otherwise v survives.
      const uint32_t kept = cand.keep == 0 ? e.u : e.v;
      const uint32_t removed = kept == e.u ? e.v : e.u;
      const Verdict verdict = CanCollapse(removed, kept, cand.position);
      if (verdict == Verdict::kRefused) continue;
      if (verdict == Verdict::kLate && e.late() &&
          c < options_.late_floor.size() &&
          component_faces_[c] <= options_.late_floor[c]) {
        continue;
      }
      if (verdict == Verdict::kLate && !e.late()) {
        queue_.push({e.cost, e.u, e.v, e.tag | kLateBit});
        continue;
      }
      faces -= Collapse(removed, kept, cand);
      if (++done % report_every == 0 && options_.progress && planned > 0) {
        options_.progress(std::min(
            1.0, static_cast<double>(done) / static_cast<double>(planned)));
      }
    }
  }

  struct Candidate {
    double cost;
    Vec3 position;
    uint8_t keep;  // 0: u's position, 1: v's position, 2: a new point
  };
  // 16 bytes: sifting the queue dominates the run time on large inputs (a
  // 1 M-face mesh makes about 6 M entries), so entries are kept small. The
  // tag holds the stamps of both ends modulo 2^15 and the "late" bit; a
  // stale entry that wraps around to a matching tag is harmless, since
  // every popped edge is evaluated and checked afresh.
  static constexpr uint32_t kLateBit = 1u << 31;
  struct Entry {
    float cost;
    uint32_t u, v;
    uint32_t tag;
    bool late() const { return (tag & kLateBit) != 0; }
    bool operator>(const Entry& o) const {
      return late() != o.late() ? late() : cost > o.cost;
    }
  };
  uint32_t Tag(uint32_t u, uint32_t v, bool late) const {
    return (stamp_[u] & 0x7fffu) | ((stamp_[v] & 0x7fffu) << 15) |
           (late ? kLateBit : 0u);
  }
  Entry MakeEntry(uint32_t u, uint32_t v, bool late) const {
    return {static_cast<float>(Evaluate(u, v).cost), u, v, Tag(u, v, late)};
  }

  // Face and boundary quadrics, boundary flags; returns the undirected
  // edges with their face counts.
  std::vector<std::pair<uint64_t, uint32_t>> InitQuadrics() {
    const int threads = options_.threads;
    // Each vertex sums its faces' planes in face order (vertex_faces_ lists
    // them so), as one pass over the faces would: the same sums for any
    // thread count.
    std::vector<Quadric> face_quadric(faces_.size());
    std::vector<Vec3> face_normal(faces_.size());  // twice the area, or 0
    ParallelFor(faces_.size(), threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; ++f) {
        const Face& t = faces_[f];
        const Vec3 n = (positions_[t[1]] - positions_[t[0]])
                           .cross(positions_[t[2]] - positions_[t[0]]);
        const double twice_area = n.norm();
        if (twice_area > 0) {
          const Vec3 unit = n / twice_area;
          face_quadric[f] =
              Quadric::Plane(unit, -unit.dot(positions_[t[0]]), twice_area / 2);
          face_normal[f] = n;
        } else {
          face_normal[f] = Vec3::Zero();
        }
      }
    });
    ParallelFor(positions_.size(), threads, [&](size_t begin, size_t end) {
      for (size_t v = begin; v < end; ++v) {
        for (uint32_t f : vertex_faces_[v]) {
          if (face_normal[f] == Vec3::Zero()) continue;
          quadrics_[v] += face_quadric[f];
          normal_sums_[v] += face_normal[f] / 2;
        }
      }
    });
    std::vector<std::pair<uint64_t, uint32_t>> keyed(faces_.size() * 3);
    ParallelFor(faces_.size(), threads, [&](size_t begin, size_t end) {
      for (size_t f = begin; f < end; ++f) {
        const Face& t = faces_[f];
        for (size_t i = 0; i < 3; ++i) {
          keyed[3 * f + i] = {EdgeKey(t[i], t[(i + 1) % 3]), static_cast<uint32_t>(f)};
        }
      }
    });
    ParallelSort(keyed.begin(), keyed.end(), threads);
    std::vector<std::pair<uint64_t, uint32_t>> edges;
    for (size_t i = 0; i < keyed.size();) {
      size_t j = i + 1;
      while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
      edges.push_back({keyed[i].first, static_cast<uint32_t>(j - i)});
      if (j - i == 1) AddBoundaryPlane(keyed[i].first, keyed[i].second);
      i = j;
    }
    return edges;
  }

  void AddBoundaryPlane(uint64_t key, uint32_t f) {
    const uint32_t a = static_cast<uint32_t>(key >> 32);
    const uint32_t b = static_cast<uint32_t>(key);
    boundary_[a] = boundary_[b] = 1;
    const Face& t = faces_[f];
    const Vec3 n = (positions_[t[1]] - positions_[t[0]])
                       .cross(positions_[t[2]] - positions_[t[0]]);
    const Vec3 edge = positions_[b] - positions_[a];
    Vec3 m = edge.cross(n);
    const double length = m.norm();
    if (!(length > 0)) return;
    m /= length;
    const Quadric q = Quadric::Plane(m, -m.dot(positions_[a]),
                                     kBoundaryWeight * edge.squaredNorm());
    quadrics_[a] += q;
    quadrics_[b] += q;
  }

  Candidate Evaluate(uint32_t u, uint32_t v) const {
    const Quadric q = quadrics_[u] + quadrics_[v];
    Candidate best{std::numeric_limits<double>::infinity(), Vec3::Zero(), 0};
    auto consider = [&](const Vec3& p, uint8_t keep) {
      const double e = q.Error(p);
      if (e < best.cost) best = {e, p, keep};
    };
    const Vec3& pu = positions_[u];
    const Vec3& pv = positions_[v];
    // A boundary or locked end must stay where it is: the collapse goes to
    // its position.
    const bool pin_u = boundary_[u] || Locked(u);
    const bool pin_v = boundary_[v] || Locked(v);
    const bool u_allowed = !Locked(v) && (boundary_[u] || !boundary_[v]);
    const bool v_allowed = !Locked(u) && (boundary_[v] || !boundary_[u]);
    if (u_allowed) consider(pu, 0);
    if (v_allowed) consider(pv, 1);
    if (!pin_u && !pin_v) {
      const Vec3 mid = (pu + pv) / 2;
      consider(mid, 2);
      Vec3 optimum;
      if (q.Minimizer(&optimum) &&
          (optimum - mid).squaredNorm() <= (pu - pv).squaredNorm()) {
        consider(optimum, 2);
      }
    }
    if (std::isinf(best.cost)) return best;  // both ends pinned apart
    const double length2 = (pu - pv).squaredNorm();
    best.cost = std::max(best.cost, 0.0) + kLengthWeight * length2 * length2;
    return best;
  }

  void Push(uint32_t u, uint32_t v) { queue_.push(MakeEntry(u, v, false)); }

  void Neighbours(uint32_t v, uint32_t skip, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t f : vertex_faces_[v]) {
      for (uint32_t x : faces_[f]) {
        if (x != v && x != skip) out.push_back(x);
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  // kLate: allowed only once no kOk collapse is left anywhere.
  enum class Verdict { kOk, kLate, kRefused };

  Verdict CanCollapse(uint32_t removed, uint32_t kept, const Vec3& p) {
    uint32_t apex[2];
    int shared = 0;
    for (uint32_t f : vertex_faces_[removed]) {
      if (!Contains(faces_[f], kept)) continue;
      if (shared == 2) return Verdict::kRefused;
      apex[shared++] = ThirdCorner(faces_[f], removed, kept);
    }
    if (shared == 0) return Verdict::kRefused;  // the edge no longer exists
    const bool both_boundary = boundary_[removed] && boundary_[kept];
    if (both_boundary && shared == 2) return Verdict::kRefused;  // would pinch
    if (shared == 1 && !both_boundary) return Verdict::kRefused;
    // Link condition: the neighbours both ends share, counted once each
    // (marks instead of two sorted rings: this test runs for every popped
    // edge).
    if (mark_.empty() || mark_stamp_ >= 0xfffffffdu) {
      mark_.assign(positions_.size(), 0);
      mark_stamp_ = 0;
    }
    mark_stamp_ += 2;
    const uint32_t in_a = mark_stamp_, counted = mark_stamp_ + 1;
    for (uint32_t f : vertex_faces_[removed]) {
      for (uint32_t x : faces_[f]) {
        if (x != removed && x != kept) mark_[x] = in_a;
      }
    }
    size_t common = 0;
    for (uint32_t f : vertex_faces_[kept]) {
      for (uint32_t x : faces_[f]) {
        if (x != removed && x != kept && mark_[x] == in_a) {
          mark_[x] = counted;
          ++common;
        }
      }
    }
    if (common != static_cast<size_t>(shared)) return Verdict::kRefused;
    // Inner vertices keep at least three faces, boundary ones at least one;
    // inner valence 3 is put off (see kMinInnerValence).
    bool late = false;
    for (int i = 0; i < shared; ++i) {
      const size_t faces = vertex_faces_[apex[i]].size() - 1;
      if (boundary_[apex[i]] ? faces < 1 : faces < 3) return Verdict::kRefused;
      if (!boundary_[apex[i]] && faces < kMinInnerValence) late = true;
    }
    const size_t after =
        vertex_faces_[removed].size() + vertex_faces_[kept].size() - 2 * shared;
    if (boundary_[removed] || boundary_[kept] ? after < 1 : after < 3) {
      return Verdict::kRefused;
    }
    if (!boundary_[removed] && !boundary_[kept] && after < kMinInnerValence) {
      late = true;
    }
    // Geometry: no fold, no new sliver worse than what is there.
    double worst_before = 1, worst_after = 1;
    double worst_normal_before = 1, worst_normal_after = 1;
    for (uint32_t moved : {removed, kept}) {
      for (uint32_t f : vertex_faces_[moved]) {
        const Face& t = faces_[f];
        if (Contains(t, removed) && Contains(t, kept)) continue;
        Vec3 corner[3], moved_corner[3];
        for (int i = 0; i < 3; ++i) {
          corner[i] = positions_[t[i]];
          moved_corner[i] = t[i] == moved ? p : corner[i];
        }
        worst_normal_before = std::min(
            worst_normal_before, CornerNormalCos(t, removed, kept, false));
        worst_normal_after = std::min(worst_normal_after,
                                      CornerNormalCos(t, removed, kept, true));
        const Vec3 before =
            (corner[1] - corner[0]).cross(corner[2] - corner[0]);
        const Vec3 after_n = (moved_corner[1] - moved_corner[0])
                                 .cross(moved_corner[2] - moved_corner[0]);
        const double nb = before.norm(), na = after_n.norm();
        if (!(na > 0)) return Verdict::kRefused;
        if (!FacesItsCorners(after_n, t, removed, kept)) {
          return Verdict::kRefused;
        }
        if (nb > 0 && before.dot(after_n) < kMinNormalCos * nb * na) {
          return Verdict::kRefused;
        }
        if (options_.max_edge_length > 0) {
          for (int i = 0; i < 3; ++i) {
            if (t[i] == moved &&
                ((moved_corner[(i + 1) % 3] - p).squaredNorm() >
                     max_edge_squared_ ||
                 (moved_corner[(i + 2) % 3] - p).squaredNorm() >
                     max_edge_squared_)) {
              late = true;
            }
          }
        }
        worst_before = std::min(worst_before,
                                Compactness(corner[0], corner[1], corner[2]));
        worst_after = std::min(
            worst_after,
            Compactness(moved_corner[0], moved_corner[1], moved_corner[2]));
      }
    }
    if (worst_after < worst_before) {
      if (worst_after < kMinQuality) return Verdict::kRefused;
      if (worst_after < kGoodQuality) late = true;
    }
    if (worst_normal_after < kMinCornerNormalCos &&
        worst_normal_after < worst_normal_before) {
      late = true;
    }
    return late ? Verdict::kLate : Verdict::kOk;
  }

  // Whether `normal` (of face t after the collapse) is within about 78° of
  // the mean input normal carried by the face's corners: the per-collapse
  // fold test alone lets a face turn over in small steps.
  bool FacesItsCorners(const Vec3& normal, const Face& t, uint32_t removed,
                       uint32_t kept) const {
    Vec3 mean = Vec3::Zero();
    for (uint32_t x : t) {
      const uint32_t v = x == removed ? kept : x;
      Vec3 n = normal_sums_[v];
      if (v == kept) n += normal_sums_[removed];
      const double length = n.norm();
      if (length > 0) mean += n / length;
    }
    const double scale = mean.norm() * normal.norm();
    return !(scale > 0) || normal.dot(mean) >= kMinCollapseFacingCos * scale;
  }

  // The smallest cosine between the input normals carried by two corners
  // of face t, with `removed` merged into `kept` when `merged`. Corners
  // whose regions' normals cancel out (a tip) say nothing.
  double CornerNormalCos(const Face& t, uint32_t removed, uint32_t kept,
                         bool merged) const {
    Vec3 n[3];
    for (int i = 0; i < 3; ++i) {
      const uint32_t v = merged && t[i] == removed ? kept : t[i];
      n[i] = normal_sums_[v];
      if (merged && v == kept) n[i] += normal_sums_[removed];
    }
    double worst = 1;
    for (int i = 0; i < 3; ++i) {
      const Vec3& a = n[i];
      const Vec3& b = n[(i + 1) % 3];
      const double scale = a.norm() * b.norm();
      if (scale > 0) worst = std::min(worst, a.dot(b) / scale);
    }
    return worst;
  }

  bool Locked(uint32_t v) const {
    return source_[v] != kNone && source_[v] < options_.locked.size() &&
           options_.locked[source_[v]] != 0;
  }

  uint32_t MinFaces(uint32_t component) const {
    return component < options_.min_faces.size() ? options_.min_faces[component]
                                                 : 0;
  }

  // Returns the number of faces removed.
  size_t Collapse(uint32_t removed, uint32_t kept, const Candidate& cand) {
    size_t removed_faces = 0;
    for (uint32_t f : vertex_faces_[removed]) {
      Face& t = faces_[f];
      if (Contains(t, kept)) {
        face_alive_[f] = 0;
        --component_faces_[component_[kept]];
        ++removed_faces;
        for (uint32_t x : t) {
          if (x == removed) continue;
          auto& list = vertex_faces_[x];
          list.erase(std::find(list.begin(), list.end(), f));
        }
        continue;
      }
      for (uint32_t& x : t) {
        if (x == removed) x = kept;
      }
      vertex_faces_[kept].push_back(f);
    }
    vertex_faces_[removed].clear();
    vertex_faces_[removed].shrink_to_fit();
    if (cand.keep == 2) {
      source_[kept] = kNone;
    }
    positions_[kept] = cand.position;
    quadrics_[kept] += quadrics_[removed];
    normal_sums_[kept] += normal_sums_[removed];
    boundary_[kept] = boundary_[kept] || boundary_[removed];
    ++stamp_[kept];
    ++stamp_[removed];  // every queued edge of `removed` is now stale
    Neighbours(kept, kNone, ring_a_);
    for (uint32_t w : ring_a_) Push(kept, w);
    return removed_faces;
  }

  SimplifiedMesh Compact(size_t collapses) const {
    SimplifiedMesh out;
    out.collapses = collapses;
    std::vector<uint32_t> index(positions_.size(), kNone);
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      if (!face_alive_[f]) continue;
      Face g;
      for (int i = 0; i < 3; ++i) {
        const uint32_t v = faces_[f][i];
        if (index[v] == kNone) {
          index[v] = static_cast<uint32_t>(out.mesh.positions.size());
          out.mesh.positions.push_back(positions_[v]);
          out.source_vertex.push_back(source_[v]);
          out.component.push_back(component_[v]);
        }
        g[i] = index[v];
      }
      out.mesh.faces.push_back(g);
    }
    return out;
  }

  const SimplifyOptions& options_;
  std::vector<Vec3> positions_;
  std::vector<Face> faces_;
  std::vector<uint8_t> face_alive_;
  std::vector<std::vector<uint32_t>> vertex_faces_;
  std::vector<Quadric> quadrics_;
  std::vector<Vec3> normal_sums_;
  std::vector<uint8_t> boundary_;
  std::vector<uint32_t> stamp_;
  std::vector<uint32_t> source_;
  std::vector<uint32_t> component_;
  std::vector<uint32_t> component_faces_;
  double max_edge_squared_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
  std::vector<uint32_t> ring_a_;
  std::vector<uint32_t> mark_;  // per vertex: CanCollapse's link-condition marks
  uint32_t mark_stamp_ = 0;
};

}  // namespace

SimplifiedMesh SimplifyByEdgeCollapse(const TriMesh& mesh,
                                      const Components& components,
                                      const SimplifyOptions& options) {
  Simplifier simplifier(mesh, components, options);
  return simplifier.Run();
}

}  // namespace meshwave::remesh
