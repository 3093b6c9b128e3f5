// CleanMesh: merge bit-identical vertices, drop degenerate and duplicate
// faces and unreferenced vertices, all stable (first occurrences win, order
// kept), and count zero-area faces without removing them.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <Eigen/Geometry>

#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"

namespace meshwave {
namespace {

inline uint64_t Mix(uint64_t h, uint64_t v) {
  // splitmix64 finaliser over a running combination: cheap and well spread.
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  return h;
}

struct PositionBits {
  uint64_t x, y, z;
  bool operator==(const PositionBits&) const = default;
};
struct PositionBitsHash {
  size_t operator()(const PositionBits& p) const {
    return static_cast<size_t>(Mix(Mix(Mix(0, p.x), p.y), p.z));
  }
};

struct SortedFace {
  uint32_t a, b, c;
  bool operator==(const SortedFace&) const = default;
};
struct SortedFaceHash {
  size_t operator()(const SortedFace& f) const {
    return static_cast<size_t>(Mix(Mix(Mix(0, f.a), f.b), f.c));
  }
};

SortedFace Sorted(const Face& f) {
  uint32_t a = f[0], b = f[1], c = f[2];
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return {a, b, c};
}

// No area: the edges are parallel to within rounding (or one has length 0).
bool HasZeroArea(const TriMesh& mesh, const Face& f) {
  const Vec3 e1 = mesh.positions[f[1]] - mesh.positions[f[0]];
  const Vec3 e2 = mesh.positions[f[2]] - mesh.positions[f[0]];
  constexpr double kRelativeSine = 1e-12;  // far below float32 resolution
  return e1.cross(e2).norm() <= kRelativeSine * e1.norm() * e2.norm();
}

// Maps each vertex to the first vertex with bit-identical coordinates.
std::vector<uint32_t> FirstOccurrences(const std::vector<Vec3>& positions,
                                       size_t* merged) {
  std::vector<uint32_t> first(positions.size());
  std::unordered_map<PositionBits, uint32_t, PositionBitsHash> seen;
  seen.reserve(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    PositionBits key{std::bit_cast<uint64_t>(p.x()),
                     std::bit_cast<uint64_t>(p.y()),
                     std::bit_cast<uint64_t>(p.z())};
    auto [it, inserted] = seen.emplace(key, static_cast<uint32_t>(i));
    first[i] = it->second;
    if (!inserted) ++*merged;
  }
  return first;
}

}  // namespace

CleanReport CleanMesh(TriMesh& mesh, const CleanOptions& options) {
  CleanReport report;
  const size_t vertex_count = mesh.positions.size();
  std::vector<uint32_t> representative;
  if (options.merge_duplicate_vertices) {
    representative = FirstOccurrences(mesh.positions, &report.merged_vertices);
    for (Face& f : mesh.faces) {
      for (uint32_t& index : f) index = representative[index];
    }
  }

  std::unordered_set<SortedFace, SortedFaceHash> seen_faces;
  if (options.drop_duplicate_faces) seen_faces.reserve(mesh.faces.size());
  size_t kept = 0;
  for (const Face& f : mesh.faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
      if (options.drop_degenerate_faces) {
        ++report.degenerate_faces;
        continue;
      }
    } else if (options.drop_duplicate_faces &&
               !seen_faces.insert(Sorted(f)).second) {
      ++report.duplicate_faces;
      continue;
    }
    mesh.faces[kept++] = f;
  }
  mesh.faces.resize(kept);

  std::vector<bool> referenced(vertex_count, false);
  for (const Face& f : mesh.faces) {
    for (uint32_t index : f) referenced[index] = true;
    bool distinct = f[0] != f[1] && f[1] != f[2] && f[0] != f[2];
    if (distinct && HasZeroArea(mesh, f)) ++report.zero_area_faces;
  }

  // Stable compaction: merged duplicates always go (nothing refers to them
  // any more); other unreferenced vertices go when asked.
  std::vector<uint32_t> new_index(vertex_count, UINT32_MAX);
  uint32_t next = 0;
  for (size_t i = 0; i < vertex_count; ++i) {
    const bool duplicate = !representative.empty() && representative[i] != i;
    if (duplicate) continue;
    if (!referenced[i]) {
      ++report.unreferenced_vertices;
      if (options.drop_unreferenced_vertices) continue;
    }
    new_index[i] = next;
    mesh.positions[next++] = mesh.positions[i];
  }
  mesh.positions.resize(next);
  for (Face& f : mesh.faces) {
    for (uint32_t& index : f) index = new_index[index];
  }
  return report;
}

}  // namespace meshwave
