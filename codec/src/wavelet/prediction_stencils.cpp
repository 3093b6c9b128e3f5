#include "wavelet/prediction_stencils.h"

#include <cmath>
#include <bit>
#include <unordered_map>
#include <numbers>

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
      hash = (hash ^ std::bit_cast<uint64_t>(x)) * 0x9E3779B97F4A7C15ull;
    }
    table.offsets.push_back(static_cast<uint32_t>(table.indices.size()));
    table.weight_start.push_back(FindOrAddRun(table, hash));
    terms_.clear();
  }

 private:
  // Start of an identical weight run already in the table, or of a new one.
  uint32_t FindOrAddRun(StencilTable& table, uint64_t hash) {
    auto& starts = runs_[hash];
    for (uint32_t start : starts) {
      bool same = start + terms_.size() <= table.weights.size();
      for (size_t i = 0; same && i < terms_.size(); ++i) {
        same = table.weights[start + i] == terms_[i].second;
      }
      if (same) return start;
    }
    const uint32_t start = static_cast<uint32_t>(table.weights.size());
    for (const auto& term : terms_) table.weights.push_back(term.second);
    starts.push_back(start);
    return start;
  }

  std::vector<std::pair<uint32_t, double>> terms_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> runs_;  // hash -> starts
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
  // Edge of face f joining u and w.
  uint32_t EdgeOf(uint32_t f, uint32_t u, uint32_t w) const {
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = faces_[f][i], b = faces_[f][(i + 1) % 3];
      if ((a == u && b == w) || (a == w && b == u)) return face_edges_[f][i];
    }
    return kNone;
  }
  // The wing across edge (u, w) of face f, whose third vertex is z: the
  // vertex opposite (u, w) in the neighbouring face, or the reflection
  // u + w - z on a boundary.
  void AddWing(StencilBuilder& s, uint32_t f, uint32_t u, uint32_t w,
               uint32_t z, double weight) const {
    const uint32_t g = EdgeOf(f, u, w);
    const auto& ef = edge_faces_[g];
    const uint32_t other = ef[0] == f ? ef[1] : ef[0];
    if (other == kNone) {
      s.Add(u, weight);
      s.Add(w, weight);
      s.Add(z, -weight);
    } else {
      s.Add(Opposite(other, g), weight);
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
      const double a = 2 * std::numbers::pi * i / k;
      w = (0.25 + std::cos(a) + 0.5 * std::cos(2 * a)) / k;
    }
    if (w != 0) s.Add(ring[(start + i) % k], w * scale);
  }
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
  view.AddWing(s, fa, c1, c3, c2, -1.0 / 16);
  view.AddWing(s, fa, c2, c3, c1, -1.0 / 16);
  view.AddWing(s, fb, c1, c4, c2, -1.0 / 16);
  view.AddWing(s, fb, c2, c4, c1, -1.0 / 16);
}

}  // namespace

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
        AddButterfly(view, s, e);
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
