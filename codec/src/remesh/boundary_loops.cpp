#include "remesh/boundary_loops.h"
#include "core/edge_key.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace meshwave::remesh {

BoundaryLoops::BoundaryLoops(const TriMesh& mesh)
    : entry_of_vertex_(mesh.positions.size(), kNone),
      positions_(&mesh.positions) {
  // Directed edges, sorted, so the twin of a -> b is found by a search.
  std::vector<std::pair<uint64_t, uint32_t>> directed;
  directed.reserve(mesh.faces.size() * 3);
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = mesh.faces[f][i], b = mesh.faces[f][(i + 1) % 3];
      directed.push_back({DirectedEdgeKey(a, b), f});
    }
  }
  std::sort(directed.begin(), directed.end());
  // next[a] = b and its face, for boundary edges a -> b (one per boundary
  // vertex of a manifold).
  std::vector<uint32_t> next(mesh.positions.size(), kNone);
  std::vector<uint32_t> next_face(mesh.positions.size(), kNone);
  std::vector<uint32_t> starts;
  for (const auto& [key, f] : directed) {
    const uint32_t a = static_cast<uint32_t>(key >> 32);
    const uint32_t b = static_cast<uint32_t>(key);
    const uint64_t twin = DirectedEdgeKey(b, a);
    auto it =
        std::lower_bound(directed.begin(), directed.end(), twin,
                         [](const auto& e, uint64_t k) { return e.first < k; });
    if (it != directed.end() && it->first == twin) continue;
    next[a] = b;
    next_face[a] = f;
    starts.push_back(a);
  }
  offsets_.push_back(0);
  for (uint32_t start : starts) {
    if (entry_of_vertex_[start] != kNone) continue;
    double arc = 0;
    uint32_t v = start;
    while (v != kNone && entry_of_vertex_[v] == kNone) {
      entry_of_vertex_[v] = static_cast<uint32_t>(vertices_.size());
      vertices_.push_back(v);
      faces_.push_back(next_face[v]);
      arc_.push_back(arc);
      const uint32_t w = next[v];
      if (w != kNone) arc += (mesh.positions[w] - mesh.positions[v]).norm();
      v = w;
    }
    lengths_.push_back(arc);
    offsets_.push_back(static_cast<uint32_t>(vertices_.size()));
  }
}

BoundaryLoops::Location BoundaryLoops::Locate(uint32_t vertex) const {
  const uint32_t e = entry_of_vertex_[vertex];
  if (e == kNone) return {};
  const auto loop = static_cast<uint32_t>(
      std::upper_bound(offsets_.begin(), offsets_.end(), e) - offsets_.begin() -
      1);
  return {loop, arc_[e]};
}

BoundaryLoops::Point BoundaryLoops::At(uint32_t loop, double s) const {
  const uint32_t begin = offsets_[loop], end = offsets_[loop + 1];
  const double length = lengths_[loop];
  if (length > 0) {
    s = std::fmod(s, length);
    if (s < 0) s += length;
  } else {
    s = 0;
  }
  // Last entry whose arc length is <= s.
  uint32_t i = static_cast<uint32_t>(
      std::upper_bound(arc_.begin() + begin, arc_.begin() + end, s) -
      arc_.begin());
  i = std::max(i, begin + 1) - 1;
  const uint32_t j = i + 1 < end ? i + 1 : begin;
  const double edge_end = i + 1 < end ? arc_[i + 1] : length;
  const double span = edge_end - arc_[i];
  const double t = span > 0 ? std::clamp((s - arc_[i]) / span, 0.0, 1.0) : 0;
  const Vec3& a = (*positions_)[vertices_[i]];
  const Vec3& b = (*positions_)[vertices_[j]];
  return {a + t * (b - a), faces_[i]};
}

double BoundaryLoops::Midway(uint32_t loop, double a, double b) const {
  const double length = lengths_[loop];
  double forward = b - a;
  if (forward <= 0) forward += length;
  double s = a + forward / 2;
  if (s >= length) s -= length;
  return s;
}

}  // namespace meshwave::remesh
