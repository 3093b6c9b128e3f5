#include "wavelet/prediction_stencils.h"

#include <cmath>
#include <numbers>
#include <unordered_map>

#include "core/bit_cast.h"
#include "core/correctly_rounded_cos.h"

namespace meshwave {
namespace {

constexpr uint32_t kNone = SemiRegularHierarchy::kNone;

// Gathers (vertex, weight) terms of one stencil, merging repeated vertices
// (small meshes: a wing can coincide with another stencil vertex).
class StencilBuilder {
 public:
  void Add(uint32_t v, double w) {
    for (auto& [u, x] : terms_) {
      if (u == v) {
        x += w;
        return;
      }
    }
    terms_.push_back({v, w});
  }
  void Flush(StencilTable& table) {
    uint64_t hash = terms_.size();
    for (const auto& [v, x] : terms_) {
      table.indices.push_back(v);
      hash = (hash ^ BitCast<uint64_t>(x)) * 0x9E3779B97F4A7C15ull;
    }
    table.offsets.push_back(static_cast<uint32_t>(table.indices.size()));
    table.weight_start.push_back(FindOrAddRun(table, hash));
    terms_.clear();
  }
  // The run of the gathered weights, without writing a stencil: for rows
  // that are written directly (the regular fast path below).
  uint32_t InternRun(StencilTable& table) {
    uint64_t hash = terms_.size();
    for (const auto& [v, x] : terms_) {
      hash = (hash ^ BitCast<uint64_t>(x)) * 0x9E3779B97F4A7C15ull;
    }
    const uint32_t start = FindOrAddHashedRun(table, hash);
    terms_.clear();
    return start;
  }

 private:
  // Start of an identical weight run already in the table, or of a new one.
  // Most stencils repeat the previous one's weights (regular vertices), so
  // that run is tried before any hashing.
  uint32_t FindOrAddRun(StencilTable& table, uint64_t hash) {
    if (last_size_ == terms_.size() && last_hash_ == hash && SameWeights(table, last_start_)) {
      return last_start_;
    }
    last_size_ = terms_.size();
    last_hash_ = hash;
    last_start_ = FindOrAddHashedRun(table, hash);
    return last_start_;
  }
  bool SameWeights(const StencilTable& table, uint32_t start) const {
    if (start + terms_.size() > table.weights.size()) return false;
    for (size_t i = 0; i < terms_.size(); ++i) {
      if (table.weights[start + i] != terms_[i].second) return false;
    }
    return true;
  }
  uint32_t FindOrAddHashedRun(StencilTable& table, uint64_t hash) {
    auto& starts = runs_[hash];
    for (uint32_t start : starts) {
      if (SameWeights(table, start)) return start;
    }
    const uint32_t start = static_cast<uint32_t>(table.weights.size());
    for (const auto& term : terms_) table.weights.push_back(term.second);
    starts.push_back(start);
    return start;
  }

  std::vector<std::pair<uint32_t, double>> terms_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> runs_;  // hash -> starts
  size_t last_size_ = 0;
  uint64_t last_hash_ = 0;
  uint32_t last_start_ = 0;
};

// Level-j topology queries the stencils need.
class LevelView {
 public:
  LevelView(const SemiRegularHierarchy& h, int j, const VertexRings& rings)
      : faces_(h.faces(j)),
        edges_(h.edges(j)),
        face_edges_(h.face_edges(j)),
        edge_faces_(h.edge_faces(j)),
        rings_(rings) {}

  // Vertex of face f opposite its edge e.
  uint32_t Opposite(uint32_t f, uint32_t e) const {
    for (int i = 0; i < 3; ++i) {
      if (face_edges_[f][i] == e) return faces_[f][(i + 2) % 3];
    }
    return kNone;
  }
  // The two wings of face f beside its edge e: across each other edge of
  // f, the vertex opposite it in the neighbouring face, or the reflection
  // of f's third corner on a boundary. Slots, not searches: this runs for
  // every edge of every level.
  void AddWings(StencilBuilder& s, uint32_t f, uint32_t e, double weight) const {
    int i = 0;
    while (face_edges_[f][i] != e) ++i;
    for (int k = 1; k <= 2; ++k) {
      const int slot = (i + k) % 3;
      const uint32_t g = face_edges_[f][slot];
      const auto& ef = edge_faces_[g];
      const uint32_t other = ef[0] == f ? ef[1] : ef[0];
      if (other == kNone) {
        // Edge (u, w) of f and f's corner z off it: reflect z.
        const uint32_t u = faces_[f][slot], w = faces_[f][(slot + 1) % 3];
        const uint32_t z = faces_[f][(slot + 2) % 3];
        s.Add(u, weight);
        s.Add(w, weight);
        s.Add(z, -weight);
      } else {
        s.Add(Opposite(other, g), weight);
      }
    }
  }
  // The boundary neighbour of boundary vertex v that is not `not_this`.
  uint32_t OtherBoundaryNeighbour(uint32_t v, uint32_t not_this) const {
    auto ring = rings_.Ring(v);
    return ring.front() != not_this ? ring.front() : ring.back();
  }
  bool Extraordinary(uint32_t v) const {
    return !rings_.IsBoundary(v) && rings_.Valence(v) != 6;
  }

  const std::vector<Face>& faces_;
  const std::vector<Edge>& edges_;
  const std::vector<std::array<uint32_t, 3>>& face_edges_;
  const std::vector<std::array<uint32_t, 2>>& edge_faces_;
  const VertexRings& rings_;
};

// Zorin's weight of ring neighbour i of a vertex of valence k >= 5, from a
// table filled once per valence (cosines are most of the set-up time
// otherwise). The cosines are correctly rounded, so that every platform
// (the WebAssembly decoder too) has the same weights to the bit.
double ZorinWeight(int k, int i) {
  thread_local std::vector<std::vector<double>> table;
  if (static_cast<size_t>(k) >= table.size()) table.resize(k + 1);
  std::vector<double>& row = table[k];
  if (row.empty()) {
    row.resize(k);
    for (int n = 0; n < k; ++n) {
      const double a = 2 * std::numbers::pi * n / k;
      row[n] = (0.25 + CorrectlyRoundedCos(a) + 0.5 * CorrectlyRoundedCos(2 * a)) / k;
    }
  }
  return row[i];
}

// Zorin's rule seen from an interior vertex v of valence K != 6 towards the
// edge's other endpoint e0, scaled by `scale` (1/2 when averaging two).
void AddExtraordinary(const LevelView& view, StencilBuilder& s, uint32_t v,
                      uint32_t e0, double scale) {
  auto ring = view.rings_.Ring(v);
  const int k = static_cast<int>(ring.size());
  int start = 0;
  while (ring[start] != e0) ++start;
  s.Add(v, 0.75 * scale);
  for (int i = 0; i < k; ++i) {
    double w;
    if (k == 3) {
      w = i == 0 ? 5.0 / 12 : -1.0 / 12;
    } else if (k == 4) {
      w = i == 0 ? 3.0 / 8 : (i == 2 ? -1.0 / 8 : 0.0);
    } else {
      w = ZorinWeight(k, i);
    }
    if (w != 0) s.Add(ring[(start + i) % k], w * scale);
  }
}

// The eight-point stencil of an interior edge whose endpoints are regular
// and whose four wings exist and are distinct from the other stencil
// vertices: the common case, written without the builder's merging and
// hashing. Same vertices and weights in the same order as AddButterfly
// gives, so the transform is bit-identical. False when it does not apply.
bool TryRegularButterfly(const LevelView& view, uint32_t e, uint32_t regular_run,
                         StencilTable& table) {
  const uint32_t fa = view.edge_faces_[e][0], fb = view.edge_faces_[e][1];
  if (fb == kNone) return false;
  const uint32_t c1 = view.edges_[e][0], c2 = view.edges_[e][1];
  if (view.Extraordinary(c1) || view.Extraordinary(c2)) return false;
  uint32_t v[8];
  v[0] = c1;
  v[1] = c2;
  int n = 4;
  for (int side = 0; side < 2; ++side) {
    const uint32_t f = side == 0 ? fa : fb;
    int i = 0;
    while (view.face_edges_[f][i] != e) ++i;
    v[2 + side] = view.faces_[f][(i + 2) % 3];
    for (int k = 1; k <= 2; ++k) {
      const uint32_t g = view.face_edges_[f][(i + k) % 3];
      const auto& ef = view.edge_faces_[g];
      const uint32_t other = ef[0] == f ? ef[1] : ef[0];
      if (other == kNone) return false;  // reflected wing: the general path
      v[n++] = view.Opposite(other, g);
    }
  }
  for (int a = 1; a < 8; ++a) {
    for (int b = 0; b < a; ++b) {
      if (v[a] == v[b]) return false;  // tiny meshes: wings coincide
    }
  }
  table.indices.insert(table.indices.end(), v, v + 8);
  table.offsets.push_back(static_cast<uint32_t>(table.indices.size()));
  table.weight_start.push_back(regular_run);
  return true;
}

void AddButterfly(const LevelView& view, StencilBuilder& s, uint32_t e) {
  const uint32_t c1 = view.edges_[e][0], c2 = view.edges_[e][1];
  const uint32_t fa = view.edge_faces_[e][0], fb = view.edge_faces_[e][1];
  if (fb == kNone) {  // boundary edge: four-point curve rule
    s.Add(c1, 9.0 / 16);
    s.Add(c2, 9.0 / 16);
    s.Add(view.OtherBoundaryNeighbour(c1, c2), -1.0 / 16);
    s.Add(view.OtherBoundaryNeighbour(c2, c1), -1.0 / 16);
    return;
  }
  const bool x1 = view.Extraordinary(c1), x2 = view.Extraordinary(c2);
  if (x1 || x2) {
    const double scale = (x1 && x2) ? 0.5 : 1.0;
    if (x1) AddExtraordinary(view, s, c1, c2, scale);
    if (x2) AddExtraordinary(view, s, c2, c1, scale);
    return;
  }
  // Eight-point rule; missing wings are reflected.
  const uint32_t c3 = view.Opposite(fa, e), c4 = view.Opposite(fb, e);
  s.Add(c1, 0.5);
  s.Add(c2, 0.5);
  s.Add(c3, 0.125);
  s.Add(c4, 0.125);
  view.AddWings(s, fa, e, -1.0 / 16);
  view.AddWings(s, fb, e, -1.0 / 16);
}

void AddSawtFilter(const LevelView& view, StencilBuilder& s, uint32_t e, SawtFilter filter) {
  const uint32_t c1 = view.edges_[e][0], c2 = view.edges_[e][1];
  const uint32_t fa = view.edge_faces_[e][0], fb = view.edge_faces_[e][1];
  if (fb == kNone) {
    if (filter == SawtFilter::kButterfly || filter == SawtFilter::kTenseButterfly) {
      const double w = filter == SawtFilter::kButterfly ? 1.0 / 16 : 1.0 / 8;
      s.Add(c1, 0.5 + w);
      s.Add(c2, 0.5 + w);
      s.Add(view.OtherBoundaryNeighbour(c1, c2), -w);
      s.Add(view.OtherBoundaryNeighbour(c2, c1), -w);
    } else {
      s.Add(c1, 0.5);
      s.Add(c2, 0.5);
    }
    return;
  }
  const uint32_t c3 = view.Opposite(fa, e), c4 = view.Opposite(fb, e);
  // Weights of (c1, c2), (c3, c4) and each wing.
  double near = 0.5, far = 0, wing = 0;
  switch (filter) {
    case SawtFilter::kButterfly: far = 1.0 / 8; wing = -1.0 / 16; break;
    case SawtFilter::kTenseButterfly: far = 1.0 / 4; wing = -1.0 / 8; break;
    case SawtFilter::kLoop: near = 3.0 / 8; far = 1.0 / 8; break;
    case SawtFilter::kEdge: break;
    case SawtFilter::kAntiEdge: near = 0; far = 0.5; break;
    case SawtFilter::kHybrid: near = 0.25; far = 0.25; break;
  }
  if (near != 0) {
    s.Add(c1, near);
    s.Add(c2, near);
  }
  if (far != 0) {
    s.Add(c3, far);
    s.Add(c4, far);
  }
  if (wing != 0) {
    view.AddWings(s, fa, e, wing);
    view.AddWings(s, fb, e, wing);
  }
}

}  // namespace

StencilTable BuildSawtStencils(const SemiRegularHierarchy& hierarchy, int j,
                               const VertexRings& rings,
                               std::span<const SawtFilter> filter_of_edge) {
  const LevelView view(hierarchy, j, rings);
  StencilTable table;
  table.offsets.reserve(view.edges_.size() + 1);
  table.offsets.push_back(0);
  table.weight_start.reserve(view.edges_.size());
  StencilBuilder s;
  for (uint32_t e = 0; e < view.edges_.size(); ++e) {
    AddSawtFilter(view, s, e, filter_of_edge[e]);
    s.Flush(table);
  }
  return table;
}

StencilTable BuildPredictionStencils(const SemiRegularHierarchy& hierarchy,
                                     int j, const VertexRings& rings,
                                     Predictor predictor) {
  const LevelView view(hierarchy, j, rings);
  const size_t num_edges = view.edges_.size();
  StencilTable table;
  table.offsets.reserve(num_edges + 1);
  table.offsets.push_back(0);
  table.indices.reserve(num_edges * (predictor == Predictor::kLinear ? 2 : 8));
  table.weight_start.reserve(num_edges);
  StencilBuilder s;
  uint32_t regular_run = 0;
  if (predictor == Predictor::kButterfly) {
    // Weights of TryRegularButterfly's rows, in its vertex order (distinct
    // placeholder vertices: only the weights are kept).
    const double w[8] = {0.5, 0.5, 0.125, 0.125, -1.0 / 16, -1.0 / 16, -1.0 / 16, -1.0 / 16};
    for (uint32_t i = 0; i < 8; ++i) s.Add(i, w[i]);
    regular_run = s.InternRun(table);
  }
  for (uint32_t e = 0; e < num_edges; ++e) {
    const uint32_t c1 = view.edges_[e][0], c2 = view.edges_[e][1];
    const uint32_t fb = view.edge_faces_[e][1];
    switch (predictor) {
      case Predictor::kLinear:
        s.Add(c1, 0.5);
        s.Add(c2, 0.5);
        break;
      case Predictor::kLoop:
        if (fb == kNone) {
          s.Add(c1, 0.5);
          s.Add(c2, 0.5);
        } else {
          s.Add(c1, 0.375);
          s.Add(c2, 0.375);
          s.Add(view.Opposite(view.edge_faces_[e][0], e), 0.125);
          s.Add(view.Opposite(fb, e), 0.125);
        }
        break;
      case Predictor::kButterfly:
        if (TryRegularButterfly(view, e, regular_run, table)) continue;
        AddButterfly(view, s, e);
        break;
      case Predictor::kSawt:  // without choices: f1 everywhere
        AddSawtFilter(view, s, e, SawtFilter::kButterfly);
        break;
    }
    s.Flush(table);
  }
  return table;
}

std::vector<std::array<double, 2>> BuildUpdateWeights(
    const SemiRegularHierarchy& hierarchy, int j, const VertexRings& rings,
    UpdateWeights update) {
  std::vector<std::array<double, 2>> weights;
  if (update == UpdateWeights::kNone) return weights;
  const auto& edges = hierarchy.edges(j);
  const auto& edge_faces = hierarchy.edge_faces(j);
  weights.resize(edges.size(), {0.125, 0.125});
  if (update == UpdateWeights::kValence) {
    // Faces around a vertex: its valence inside, one less on a boundary.
    auto faces_around = [&](uint32_t v) {
      return static_cast<double>(rings.Valence(v) - (rings.IsBoundary(v) ? 1 : 0));
    };
    for (size_t e = 0; e < edges.size(); ++e) {
      const double odd_faces = edge_faces[e][1] == kNone ? 3.0 : 6.0;
      for (int i = 0; i < 2; ++i) {
        weights[e][i] = odd_faces / (8.0 * faces_around(edges[e][i]));
      }
    }
  }
  return weights;
}

}  // namespace meshwave
