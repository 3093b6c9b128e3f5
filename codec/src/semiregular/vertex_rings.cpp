#include "semiregular/vertex_rings.h"

#include <algorithm>
#include <string>
#include <utility>

namespace meshwave {
namespace {

// Fans of at most this many faces are searched linearly (see below).
constexpr size_t kLinearFan = 12;

}  // namespace

Result<VertexRings> VertexRings::Build(uint32_t vertex_count,
                                       std::span<const Face> faces) {
  // Incident faces per vertex, as (next, previous) corner pairs: a face
  // (v, a, b) seen from v contributes the wedge a -> b.
  std::vector<uint32_t> face_offsets(size_t{vertex_count} + 1, 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    const Face& t = faces[f];
    for (int i = 0; i < 3; ++i) {
      if (t[i] >= vertex_count) {
        return InvalidArgument("face " + std::to_string(f) + ": vertex " +
                               std::to_string(t[i]) + " out of range");
      }
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) {
      return InvalidArgument("face " + std::to_string(f) +
                             " repeats a corner");
    }
    for (int i = 0; i < 3; ++i) ++face_offsets[t[i] + 1];
  }
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (face_offsets[v + 1] == 0) {
      return InvalidArgument("vertex " + std::to_string(v) +
                             " is not used by any face");
    }
    face_offsets[v + 1] += face_offsets[v];
  }
  std::vector<std::pair<uint32_t, uint32_t>> wedges(face_offsets.back());
  {
    std::vector<uint32_t> fill(face_offsets.begin(), face_offsets.end() - 1);
    for (const Face& t : faces) {
      for (int i = 0; i < 3; ++i) {
        wedges[fill[t[i]]++] = {t[(i + 1) % 3], t[(i + 2) % 3]};
      }
    }
  }

  VertexRings rings;
  rings.offsets_.assign(size_t{vertex_count} + 1, 0);
  rings.boundary_.assign(vertex_count, 0);
  rings.neighbours_.reserve(wedges.size() + vertex_count);
  std::vector<std::pair<uint32_t, uint32_t>> local;
  std::vector<uint32_t> ends;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    local.assign(wedges.begin() + face_offsets[v],
                 wedges.begin() + face_offsets[v + 1]);
    const size_t n = local.size();
    // Small fans (every vertex of a semi-regular mesh but the extraordinary
    // ones) are searched linearly; large ones are sorted by start vertex and
    // binary-searched, linear in valence·log(valence) even for huge fans.
    // Both find the same wedges, so the rings are the same.
    const bool sorted = n > kLinearFan;
    if (sorted) std::sort(local.begin(), local.end());
    for (size_t i = 1; i < n; ++i) {
      const size_t from = sorted ? i - 1 : 0;
      for (size_t k = from; k < i; ++k) {
        if (local[i].first == local[k].first) {
          return Status(StatusCode::kNotManifold,
                        "edge (" + std::to_string(v) + ", " +
                            std::to_string(local[i].first) +
                            ") is used by more than two faces or by two faces "
                            "of opposite orientation");
        }
      }
    }
    auto find_wedge = [&](uint32_t first) -> size_t {
      if (!sorted) {
        for (size_t i = 0; i < n; ++i) {
          if (local[i].first == first) return i;
        }
        return n;
      }
      auto it = std::lower_bound(
          local.begin(), local.end(), first,
          [](const auto& w, uint32_t x) { return w.first < x; });
      return (it != local.end() && it->first == first)
                 ? static_cast<size_t>(it - local.begin())
                 : n;
    };
    auto ends_somewhere = [&](uint32_t x) {
      if (!sorted) {
        for (const auto& w : local) {
          if (w.second == x) return true;
        }
        return false;
      }
      return std::binary_search(ends.begin(), ends.end(), x);
    };
    // A wedge starts the fan when no wedge ends where it starts.
    if (sorted) {
      ends.clear();
      for (const auto& w : local) ends.push_back(w.second);
      std::sort(ends.begin(), ends.end());
    }
    size_t start = n;
    for (size_t i = 0; i < n; ++i) {
      if (!ends_somewhere(local[i].first)) {
        if (start != n) {
          return Status(StatusCode::kNotManifold,
                        "vertex " + std::to_string(v) +
                            " joins several fans of faces (non-manifold vertex)");
        }
        start = i;
      }
    }
    const bool boundary = start != n;
    if (!boundary) {
      // A closed fan starts at its wedge of the smallest start vertex (the
      // first one once sorted).
      start = 0;
      for (size_t i = 1; i < n && !sorted; ++i) {
        if (local[i].first < local[start].first) start = i;
      }
    }
    size_t current = start;
    size_t visited = 0;
    rings.neighbours_.push_back(local[current].first);
    while (true) {
      ++visited;
      const uint32_t next_vertex = local[current].second;
      const size_t next = find_wedge(next_vertex);
      if (next == n || next == start || visited > n) {
        if (boundary) rings.neighbours_.push_back(next_vertex);
        break;
      }
      rings.neighbours_.push_back(next_vertex);
      current = next;
    }
    if (visited != n) {
      return Status(StatusCode::kNotManifold,
                    "vertex " + std::to_string(v) +
                        " joins several fans of faces (non-manifold vertex)");
    }
    rings.boundary_[v] = boundary ? 1 : 0;
    rings.offsets_[v + 1] = static_cast<uint32_t>(rings.neighbours_.size());
  }
  return rings;
}

}  // namespace meshwave
