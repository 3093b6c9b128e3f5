// FitLeastSquares: normal offsets of the finest vertices by Gauss-Newton
// rounds on a symmetric point-to-plane distance energy.
#include "remesh/fit_least_squares.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/parallel_for.h"
#include "metrics/triangle_bvh.h"
#include "remesh/remesh_quality.h"

namespace meshwave::remesh {
namespace {

// A sample whose nearest point lies on a face turned more than 60° from
// the sample's own normal is on another sheet (a thin part, a fold): the
// normal offsets cannot bring the two together, so it is left out.
constexpr double kMinSheetCos = 0.5;
// A vertex backs off while one of its faces turns more than 60° from the
// fitted face (the offsets are a small correction, never a re-shaping).
constexpr double kMinTurnCos = 0.5;
constexpr int kHalvings = 4;
// A face whose normal makes more than ~72° with the input face under one of
// its corners is checked exactly for being turned against the input.
// So is a face turned more than ~10° by the offsets (on horse_cyberware's
// ears a face whose corners' input faces all agree with it flipped at 17°:
// the input under its centroid is the other side of a thin fold).
constexpr double kSuspectCos = 0.3;
constexpr double kSuspectTurnCos = 0.985;
// Weight of the Tikhonov term (per unit of vertex area): only there so the
// system stays positive definite where a vertex has no sample at all.
constexpr double kTikhonov = 1e-6;
// Input samples are projected in blocks of this many, each block's queries
// hinted by the face found for the block's previous sample: blocks do not
// depend on the thread count, so neither do ties between equally near faces.
constexpr size_t kHintBlock = 256;
constexpr int kMaxCgIterations = 300;
constexpr double kCgRelativeResidual = 1e-8;

Eigen::Vector3d Barycentric(const Vec3& p, const Vec3& a, const Vec3& b,
                            const Vec3& c) {
  const Vec3 e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  if (!(det > 0)) return Eigen::Vector3d::Constant(1.0 / 3);
  Eigen::Vector3d beta;
  beta[1] = (d11 * d20 - d01 * d21) / det;
  beta[2] = (d00 * d21 - d01 * d20) / det;
  beta[0] = 1 - beta[1] - beta[2];
  beta = beta.cwiseMax(0.0);
  const double sum = beta.sum();
  return sum > 0 ? Eigen::Vector3d(beta / sum)
                 : Eigen::Vector3d::Constant(1.0 / 3);
}

// A symmetric matrix with the finest level's pattern: row v stores its
// diagonal, then one entry per ring neighbour in ring order.
class RingMatrix {
 public:
  static constexpr size_t kNone = std::numeric_limits<size_t>::max();

  explicit RingMatrix(const VertexRings& rings) : rings_(rings) {
    const uint32_t n = rings.vertex_count();
    start_.assign(size_t{n} + 1, 0);
    for (uint32_t v = 0; v < n; ++v) {
      start_[v + 1] = start_[v] + 1 + rings.Valence(v);
    }
    values_.assign(start_[n], 0);
  }

  size_t Slot(uint32_t i, uint32_t j) const {
    if (i == j) return start_[i];
    const std::span<const uint32_t> ring = rings_.Ring(i);
    for (size_t k = 0; k < ring.size(); ++k) {
      if (ring[k] == j) return start_[i] + 1 + k;
    }
    return kNone;
  }
  size_t slots() const { return values_.size(); }
  void Clear() { std::fill(values_.begin(), values_.end(), 0.0); }
  void AddDiagonal(uint32_t v, double x) { values_[start_[v]] += x; }
  double Diagonal(uint32_t v) const { return values_[start_[v]]; }
  void SetDiagonal(uint32_t v, double x) { values_[start_[v]] = x; }
  // Adds x at (i, j) and (j, i), i != j neighbours.
  void AddPair(uint32_t i, uint32_t j, double x) {
    const size_t a = Slot(i, j), b = Slot(j, i);
    if (a == kNone || b == kNone) return;
    values_[a] += x;
    values_[b] += x;
  }

  void Multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                int threads) const {
    ParallelFor(
        static_cast<size_t>(x.size()), threads,
        [&](size_t begin, size_t end) {
          for (size_t v = begin; v < end; ++v) {
            const std::span<const uint32_t> ring =
                rings_.Ring(static_cast<uint32_t>(v));
            const double* row = values_.data() + start_[v];
            double sum = row[0] * x[static_cast<Eigen::Index>(v)];
            for (size_t k = 0; k < ring.size(); ++k)
              sum += row[1 + k] * x[ring[k]];
            y[static_cast<Eigen::Index>(v)] = sum;
          }
        },
        16384);
  }

 private:
  const VertexRings& rings_;
  std::vector<size_t> start_;
  std::vector<double> values_;
};

// Solves H x = b (H symmetric positive definite) by conjugate gradients
// with a Jacobi preconditioner. The reductions are serial, so the result
// is the same for any thread count.
Eigen::VectorXd SolveConjugateGradients(const RingMatrix& h,
                                        const Eigen::VectorXd& b, int threads) {
  const Eigen::Index n = b.size();
  Eigen::VectorXd inverse_diagonal(n);
  for (Eigen::Index v = 0; v < n; ++v) {
    inverse_diagonal[v] = 1 / h.Diagonal(static_cast<uint32_t>(v));
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd r = b;
  Eigen::VectorXd z = inverse_diagonal.cwiseProduct(r);
  Eigen::VectorXd p = z;
  Eigen::VectorXd q(n);
  double rz = r.dot(z);
  const double stop =
      kCgRelativeResidual * kCgRelativeResidual * b.squaredNorm();
  for (int it = 0; it < kMaxCgIterations && r.squaredNorm() > stop; ++it) {
    h.Multiply(p, q, threads);
    const double pq = p.dot(q);
    if (!(pq > 0)) break;
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    z = inverse_diagonal.cwiseProduct(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return x;
}

// One linearised residual r(δ) = r0 + Σ a_k δ_k over up to three vertices.
struct Term {
  std::array<uint32_t, 3> v{};
  std::array<double, 3> a{};
  double r0 = 0;
  double weight = 0;  // 0: left out
};

// A fixed sample of the input surface.
struct InputSample {
  Vec3 point;
  Vec3 normal;  // unit
  double weight;
  uint32_t component;
};

// The input's vertices (area/12 of every incident face) and face centroids
// (3/4 of the face's area), a rule exact for quadratics over each face,
// face by face so consecutive samples are near each other. Each sample is
// made when asked for from a list of 8 bytes a sample and what its vertex
// needs (its unit normal, weight and component), so that a 10 M-face input
// holds 0.3 GiB here rather than 15 M whole samples (1 GiB).
class InputSamples {
 public:
  explicit InputSamples(const InputSurface& surface) : surface_(surface) {
    const TriMesh& mesh = surface.mesh();
    const size_t nv = mesh.positions.size();
    vertex_weight_.assign(nv, 0);
    vertex_normal_.assign(nv, Vec3::Zero());
    vertex_component_.assign(nv, 0);
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const double area = FaceArea(f);
      for (uint32_t v : mesh.faces[f]) {
        vertex_weight_[v] += area / 12;
        vertex_normal_[v] +=
            area * surface.FaceNormal(static_cast<uint32_t>(f));
      }
    }
    refs_.reserve(nv + mesh.faces.size());
    std::vector<uint8_t> seen(nv, 0);
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      if (FaceArea(f) > 0) refs_.push_back(f);
      for (uint32_t v : mesh.faces[f]) {
        if (seen[v]) continue;
        seen[v] = 1;
        const double length = vertex_normal_[v].norm();
        if (!(vertex_weight_[v] > 0) || !(length > 0)) continue;
        vertex_normal_[v] /= length;
        vertex_component_[v] = surface.components().of_face[f];
        refs_.push_back(kVertex | v);
      }
    }
  }

  size_t size() const { return refs_.size(); }

  InputSample operator[](size_t s) const {
    const TriMesh& mesh = surface_.mesh();
    const uint64_t ref = refs_[s];
    if ((ref & kVertex) != 0) {
      const auto v = static_cast<uint32_t>(ref);
      return {mesh.positions[v], vertex_normal_[v], vertex_weight_[v],
              vertex_component_[v]};
    }
    const auto f = static_cast<uint32_t>(ref);
    const Face& t = mesh.faces[f];
    return {
        (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) /
            3,
        surface_.FaceNormal(f), 3 * FaceArea(f) / 4,
        surface_.components().of_face[f]};
  }

 private:
  static constexpr uint64_t kVertex = uint64_t{1} << 32;

  double FaceArea(size_t f) const {
    const TriMesh& mesh = surface_.mesh();
    const Face& t = mesh.faces[f];
    return (mesh.positions[t[1]] - mesh.positions[t[0]])
               .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
               .norm() /
           2;
  }

  const InputSurface& surface_;
  std::vector<double> vertex_weight_;
  std::vector<Vec3> vertex_normal_;  // unit once the samples are listed
  std::vector<uint32_t> vertex_component_;
  std::vector<uint64_t> refs_;  // a face, or kVertex | a vertex
};

class LeastSquaresFit {
 public:
  LeastSquaresFit(const FitState& state, const VertexRings& rings)
      : state_(state),
        rings_(rings),
        faces_(state.hierarchy.faces(state.hierarchy.levels())),
        n_(state.hierarchy.vertex_count(state.hierarchy.levels())),
        threads_(state.options.threads),
        h_(rings) {}

  LeastSquaresStats Run() {
    LeastSquaresStats stats;
    const std::vector<Vec3>& positions = state_.positions;
    x0_.assign(positions.begin(), positions.begin() + n_);
    normal_ = VertexNormals(faces_, x0_, n_);
    SetUpVertices(stats);
    SetUpEdges();
    if (stats.free_vertices == 0) return stats;
    const InputSamples input(state_.surface);
    input_hint_.assign(input.size(), metrics::TriangleBvh::kNoFace);
    t_.assign(n_, 0);
    for (int round = 0; round < state_.options.least_squares_rounds; ++round) {
      const std::vector<Vec3> x = Positions(t_);
      h_.Clear();
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n_);
      stats.input_samples = AddInputTerms(input, x, g);
      stats.remesh_samples = AddRemeshTerms(x, g);
      AddRegularisation(g);
      const Eigen::VectorXd delta = SolveConjugateGradients(h_, -g, threads_);
      std::vector<double> next(n_);
      for (uint32_t v = 0; v < n_; ++v) {
        const double t = t_[v] + delta[v];
        next[v] = std::clamp(t, -limit_[v], limit_[v]);
        if (round + 1 == state_.options.least_squares_rounds && next[v] != t) {
          ++stats.clamped;
        }
      }
      stats.backed_off += BackOff(next);
      t_ = std::move(next);
    }
    double sum = 0;
    for (uint32_t v = 0; v < n_; ++v) {
      if (free_[v]) sum += std::abs(t_[v]);
      state_.positions[v] = x0_[v] + t_[v] * normal_[v];
    }
    stats.mean_offset = sum / static_cast<double>(stats.free_vertices);
    return stats;
  }

 private:
  std::vector<Vec3> Positions(const std::vector<double>& t) const {
    std::vector<Vec3> x(n_);
    for (uint32_t v = 0; v < n_; ++v) x[v] = x0_[v] + t[v] * normal_[v];
    return x;
  }

  // The normal equations H δ = -g of the energy linearised at t_ are summed
  // in sample order: input samples, remesh samples, then the smoothness and
  // Tikhonov terms. The samples are projected in batches (whole hint
  // blocks) on the threads and added as each batch is done, so only one
  // batch of terms is held: for a 10 M-face input the terms of all samples
  // would be about 0.8 GiB each way.
  static constexpr size_t kTermBatch = 4096 * kHintBlock;

  // Adds one sample's term to h_ and g; whether it was used.
  bool AddTerm(const Term& term, Eigen::VectorXd& g) {
    if (!(term.weight > 0)) return false;
    for (int k = 0; k < 3; ++k) {
      if (term.a[k] == 0) continue;
      g[term.v[k]] += term.weight * term.a[k] * term.r0;
      h_.AddDiagonal(term.v[k], term.weight * term.a[k] * term.a[k]);
      for (int l = k + 1; l < 3; ++l) {
        if (term.a[l] == 0 || term.v[l] == term.v[k]) continue;
        h_.AddPair(term.v[k], term.v[l], term.weight * term.a[k] * term.a[l]);
      }
    }
    return true;
  }

  // Free vertices, their offset limits and areas, the faces' fitted normals.
  void SetUpVertices(LeastSquaresStats& stats) {
    free_.assign(n_, 0);
    limit_.assign(n_, std::numeric_limits<double>::infinity());
    area_.assign(n_, 0);
    fitted_normal_.resize(faces_.size());
    for (size_t f = 0; f < faces_.size(); ++f) {
      const Face& t = faces_[f];
      fitted_normal_[f] = (x0_[t[1]] - x0_[t[0]]).cross(x0_[t[2]] - x0_[t[0]]);
      for (uint32_t v : t) area_[v] += fitted_normal_[f].norm() / 6;
    }
    for (uint32_t v = 0; v < n_; ++v) {
      double shortest = std::numeric_limits<double>::infinity();
      for (uint32_t u : rings_.Ring(v)) {
        shortest = std::min(shortest, (x0_[u] - x0_[v]).norm());
      }
      limit_[v] = state_.options.least_squares_max_offset * shortest;
      free_[v] = !rings_.IsBoundary(v) &&
                 state_.anchors[v].loop == BoundaryLoops::kNone &&
                 normal_[v].squaredNorm() > 0 && limit_[v] > 0 &&
                 std::isfinite(limit_[v]);
      if (!free_[v]) limit_[v] = 0;
      stats.free_vertices += free_[v];
    }
  }

  // Every edge once (i < j, in vertex order) with its midpoint weight, a
  // third of each adjacent face's area.
  void SetUpEdges() {
    std::vector<double> slot_area(h_.slots(), 0);
    for (size_t f = 0; f < faces_.size(); ++f) {
      const double a = fitted_normal_[f].norm() / 2;
      for (int k = 0; k < 3; ++k) {
        const uint32_t i = std::min(faces_[f][k], faces_[f][(k + 1) % 3]);
        const uint32_t j = std::max(faces_[f][k], faces_[f][(k + 1) % 3]);
        const size_t slot = h_.Slot(i, j);
        if (slot != RingMatrix::kNone) slot_area[slot] += a / 3;
      }
    }
    edges_.clear();
    for (uint32_t i = 0; i < n_; ++i) {
      for (uint32_t j : rings_.Ring(i)) {
        if (j > i) edges_.push_back({i, j, slot_area[h_.Slot(i, j)]});
      }
    }
  }

  // Input samples to their nearest point on the current remesh, the
  // residual along that face's normal; returns the samples used.
  size_t AddInputTerms(const InputSamples& input, const std::vector<Vec3>& x,
                       Eigen::VectorXd& g) {
    const metrics::TriangleBvh bvh(x, faces_, threads_);
    std::vector<Vec3> unit(faces_.size());
    for (size_t f = 0; f < faces_.size(); ++f) {
      const Face& t = faces_[f];
      const Vec3 c = (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]);
      const double length = c.norm();
      unit[f] = length > 0 ? Vec3(c / length) : Vec3::Zero();
    }
    size_t used = 0;
    std::vector<Term> terms;
    for (size_t first = 0; first < input.size(); first += kTermBatch) {
      const size_t count = std::min(kTermBatch, input.size() - first);
      terms.assign(count, Term{});
      const size_t blocks = (count + kHintBlock - 1) / kHintBlock;
      ParallelFor(
          blocks, threads_,
          [&](size_t begin, size_t end) {
            for (size_t b = begin; b < end; ++b) {
              uint32_t hint = metrics::TriangleBvh::kNoFace;
              const size_t last = std::min(count, (b + 1) * kHintBlock);
              for (size_t i = b * kHintBlock; i < last; ++i) {
                const size_t s = first + i;
                if (input_hint_[s] != metrics::TriangleBvh::kNoFace) {
                  hint = input_hint_[s];
                }
                const InputSample sample = input[s];
                const metrics::TriangleBvh::Hit hit =
                    bvh.ClosestPoint(sample.point, hint);
                if (hit.face == metrics::TriangleBvh::kNoFace) continue;
                hint = hit.face;
                input_hint_[s] = hit.face;
                terms[i] = InputTerm(sample, hit, x, unit[hit.face]);
              }
            }
          },
          16);
      for (const Term& term : terms) used += AddTerm(term, g) ? 1 : 0;
    }
    return used;
  }

  Term InputTerm(const InputSample& sample,
                 const metrics::TriangleBvh::Hit& hit,
                 const std::vector<Vec3>& x, const Vec3& m) const {
    Term term;
    const Face& t = faces_[hit.face];
    if (m.dot(sample.normal) < kMinSheetCos ||
        state_.anchors[t[0]].component != sample.component) {
      return term;
    }
    const Vec3 d = hit.point - sample.point;
    // Far from the face's own size: a part the remesh missed, which no
    // normal offset of these corners mends.
    const double size =
        std::max({(x[t[1]] - x[t[0]]).norm(), (x[t[2]] - x[t[1]]).norm(),
                  (x[t[0]] - x[t[2]]).norm()});
    if (d.norm() > size) return term;
    const Eigen::Vector3d beta =
        Barycentric(hit.point, x[t[0]], x[t[1]], x[t[2]]);
    for (int k = 0; k < 3; ++k) {
      term.v[k] = t[k];
      term.a[k] = free_[t[k]] ? beta[k] * normal_[t[k]].dot(m) : 0;
    }
    term.r0 = d.dot(m);
    term.weight = sample.weight;
    return term;
  }

  // Remesh edge midpoints to their nearest point on the input, the
  // residual along the input face's normal; returns the samples used.
  size_t AddRemeshTerms(const std::vector<Vec3>& x, Eigen::VectorXd& g) {
    const InputSurface& surface = state_.surface;
    size_t used = 0;
    std::vector<Term> terms;
    for (size_t first = 0; first < edges_.size(); first += kTermBatch) {
      const size_t count = std::min(kTermBatch, edges_.size() - first);
      terms.assign(count, Term{});
      ParallelFor(
          count, threads_,
          [&](size_t begin, size_t end) {
            for (size_t e = first + begin; e < first + end; ++e) {
              const Edge& edge = edges_[e];
              const uint32_t i = edge.i, j = edge.j;
              if (!(free_[i] || free_[j]) || !(edge.weight > 0)) continue;
              const Vec3 y = (x[i] + x[j]) / 2;
              const InputSurface::Projection hit =
                  surface.ClosestAnywhere(y, state_.anchors[i].face);
              if (!hit.found()) continue;
              const Vec3& m = surface.FaceNormal(hit.face);
              const Vec3 facing = normal_[i] + normal_[j];
              if (m.dot(facing) < kMinSheetCos * facing.norm() ||
                  surface.components().of_face[hit.face] !=
                      state_.anchors[i].component) {
                continue;
              }
              const Vec3 d = y - hit.point;
              if (d.norm() > (x[i] - x[j]).norm()) continue;
              Term& term = terms[e - first];
              term.v = {i, j, j};
              term.a = {free_[i] ? normal_[i].dot(m) / 2 : 0,
                        free_[j] ? normal_[j].dot(m) / 2 : 0, 0};
              term.r0 = d.dot(m);
              term.weight = edge.weight;
            }
          },
          1024);
      for (const Term& term : terms) used += AddTerm(term, g) ? 1 : 0;
    }
    return used;
  }

  // The smoothness and Tikhonov terms, after the samples'; fixed vertices
  // get the identity.
  void AddRegularisation(Eigen::VectorXd& g) {
    const double smoothness = state_.options.least_squares_smoothness;
    for (const Edge& edge : edges_) {
      const double w = smoothness * (x0_[edge.i] - x0_[edge.j]).squaredNorm();
      const double difference = t_[edge.i] - t_[edge.j];
      if (free_[edge.i]) {
        h_.AddDiagonal(edge.i, w);
        g[edge.i] += w * difference;
      }
      if (free_[edge.j]) {
        h_.AddDiagonal(edge.j, w);
        g[edge.j] -= w * difference;
      }
      if (free_[edge.i] && free_[edge.j]) h_.AddPair(edge.i, edge.j, -w);
    }
    for (uint32_t v = 0; v < n_; ++v) {
      if (!free_[v]) {
        h_.SetDiagonal(v, 1);
        g[v] = 0;
        continue;
      }
      const double w = kTikhonov * area_[v];
      h_.AddDiagonal(v, w);
      g[v] += w * t_[v];
      if (!(h_.Diagonal(v) > 0)) h_.SetDiagonal(v, 1);
    }
  }

  // Whether face f, at offsets t, has turned more than allowed from its
  // fitted self.
  bool Turned(size_t f, const std::vector<double>& t) const {
    const Vec3& n0 = fitted_normal_[f];
    const double n0_length = n0.norm();
    if (!(n0_length > 0)) return false;
    const std::array<Vec3, 3> p = Corners(f, t);
    const Vec3 n1 = (p[1] - p[0]).cross(p[2] - p[0]);
    return n1.dot(n0) < kMinTurnCos * n1.norm() * n0_length;
  }

  // Face f's corners at offsets t.
  std::array<Vec3, 3> Corners(size_t f, const std::vector<double>& t) const {
    std::array<Vec3, 3> p;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = faces_[f][k];
      p[k] = x0_[v] + t[v] * normal_[v];
    }
    return p;
  }

  // Whether face f at offsets t is turned against the input (IsFlipped,
  // the test MeasureQuality applies) when it is not at t_. Only faces near
  // perpendicular to the input at a corner are looked at: the offsets turn
  // the others too little to flip them.
  bool NewlyFlipped(size_t f, const std::vector<double>& t,
                    int8_t& flipped_before) const {
    const Face& c = faces_[f];
    if (t[c[0]] == t_[c[0]] && t[c[1]] == t_[c[1]] && t[c[2]] == t_[c[2]]) {
      return false;
    }
    const std::array<Vec3, 3> p = Corners(f, t);
    const Vec3 n = (p[1] - p[0]).cross(p[2] - p[0]);
    const Vec3& n0 = fitted_normal_[f];
    bool suspect = n.dot(n0) < kSuspectTurnCos * n.norm() * n0.norm();
    for (uint32_t v : c) {
      const uint32_t face = state_.anchors[v].face;
      if (face == InputSurface::kNoFace ||
          n.dot(state_.surface.FaceNormal(face)) < kSuspectCos * n.norm()) {
        suspect = true;
      }
    }
    if (!suspect) return false;
    const uint32_t component = state_.anchors[c[0]].component;
    // No hint, as MeasureQuality: on a thin part the nearest input point
    // can tie between faces of different normals.
    const uint32_t hint = InputSurface::kNoFace;
    if (!IsFlipped(state_.surface, p[0], p[1], p[2], component, hint)) {
      return false;
    }
    if (flipped_before < 0) {
      const std::array<Vec3, 3> q = Corners(f, t_);
      flipped_before =
          IsFlipped(state_.surface, q[0], q[1], q[2], component, hint) ? 1 : 0;
    }
    return flipped_before == 0;
  }

  // The corners of faces turned too far (Turned) or newly flipped against
  // the input (NewlyFlipped) go halfway back to t_, kHalvings times, then
  // all the way (t_ itself has neither). Returns how many vertices backed
  // off.
  size_t BackOff(std::vector<double>& next) const {
    std::vector<uint8_t> marked(n_, 0);
    std::vector<uint8_t> bad(faces_.size(), 0);
    std::vector<int8_t> flipped_before(faces_.size(), -1);
    for (int step = 0;; ++step) {
      ParallelFor(
          faces_.size(), threads_,
          [&](size_t begin, size_t end) {
            for (size_t f = begin; f < end; ++f) {
              bad[f] =
                  Turned(f, next) || NewlyFlipped(f, next, flipped_before[f]);
            }
          },
          16384);
      bool any = false;
      std::vector<uint8_t> move(n_, 0);
      for (size_t f = 0; f < faces_.size(); ++f) {
        if (!bad[f]) continue;
        for (uint32_t v : faces_[f]) {
          if (free_[v] && next[v] != t_[v]) move[v] = 1;
        }
      }
      for (uint32_t v = 0; v < n_; ++v) {
        if (!move[v]) continue;
        any = true;
        marked[v] = 1;
        next[v] = step < kHalvings ? (next[v] + t_[v]) / 2 : t_[v];
      }
      if (!any) break;
    }
    return static_cast<size_t>(std::count(marked.begin(), marked.end(), 1));
  }

  struct Edge {
    uint32_t i, j;
    double weight;
  };

  const FitState& state_;
  const VertexRings& rings_;
  const std::vector<Face>& faces_;
  const uint32_t n_;
  const int threads_;
  RingMatrix h_;
  std::vector<Vec3> x0_;
  std::vector<Vec3> normal_;
  std::vector<Vec3> fitted_normal_;  // unnormalised
  std::vector<uint8_t> free_;
  std::vector<double> limit_;
  std::vector<double> area_;
  std::vector<Edge> edges_;
  std::vector<double> t_;
  std::vector<uint32_t> input_hint_;
};

}  // namespace

LeastSquaresStats FitLeastSquares(const FitState& state,
                                  const VertexRings& rings) {
  if (state.options.least_squares_rounds <= 0) return {};
  return LeastSquaresFit(state, rings).Run();
}

}  // namespace meshwave::remesh
