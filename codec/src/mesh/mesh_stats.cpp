// ComputeStats: edges from half-edges bucketed by their smaller vertex
// (a counting sort, then tiny per-vertex sorts), and union-find for
// components, boundary loops and the fans around each vertex. Linear apart
// from the per-vertex sorts, so a 270k-face mesh takes a few milliseconds.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/mesh_stats.h"

namespace meshwave {
namespace {

class UnionFind {
 public:
  explicit UnionFind(size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), uint32_t{0});
  }
  uint32_t Find(uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];  // path halving
      x = parent_[x];
    }
    return x;
  }
  void Union(uint32_t a, uint32_t b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    parent_[a] = b;  // the smaller index becomes the root
  }

 private:
  std::vector<uint32_t> parent_;
};

// A half-edge of face corner `corner` (face corner / 3, slot corner % 3),
// running to the next corner of the face; filed under its smaller vertex.
struct HalfEdge {
  uint32_t other;   // the larger vertex of the edge
  uint32_t corner;  // the corner the half-edge starts at
};

uint32_t NextCorner(uint32_t corner) {
  return corner % 3 == 2 ? corner - 2 : corner + 1;
}

class StatsBuilder {
 public:
  explicit StatsBuilder(const TriMesh& mesh)
      : mesh_(mesh),
        vertex_count_(mesh.positions.size()),
        on_boundary_(vertex_count_, false),
        fans_(3 * mesh.faces.size()),
        boundary_graph_(vertex_count_),
        components_(vertex_count_) {}

  MeshStats Build() {
    CountVertices();
    BucketHalfEdges();
    ScanEdges();
    CountFansAndComponents();
    stats_.faces = mesh_.faces.size();
    stats_.manifold =
        stats_.non_manifold_edges == 0 && stats_.non_manifold_vertices == 0;
    stats_.closed = stats_.manifold && stats_.boundary_edges == 0;
    stats_.euler_characteristic = static_cast<long>(stats_.vertices) -
                                  static_cast<long>(stats_.edges) +
                                  static_cast<long>(stats_.faces);
    if (stats_.manifold) {
      // Each component is a surface with boundary: chi = 2 - 2g - b.
      long twice_genus = 2 * static_cast<long>(stats_.components) -
                         stats_.euler_characteristic -
                         static_cast<long>(stats_.boundary_loops);
      stats_.genus = twice_genus / 2;
    }
    return stats_;
  }

 private:
  uint32_t VertexAt(uint32_t corner) const {
    return mesh_.faces[corner / 3][corner % 3];
  }

  void CountVertices() {
    referenced_.assign(vertex_count_, false);
    for (const Face& f : mesh_.faces) {
      for (uint32_t v : f) referenced_[v] = true;
    }
    stats_.vertices = static_cast<size_t>(
        std::count(referenced_.begin(), referenced_.end(), true));
    stats_.unreferenced_vertices = vertex_count_ - stats_.vertices;
  }

  // Counting sort of the half-edges by their smaller vertex; self-loops (a
  // corner repeated in a degenerate face) are no edges and are left out.
  void BucketHalfEdges() {
    bucket_start_.assign(vertex_count_ + 1, 0);
    const uint32_t corners = static_cast<uint32_t>(3 * mesh_.faces.size());
    for (uint32_t c = 0; c < corners; ++c) {
      uint32_t a = VertexAt(c), b = VertexAt(NextCorner(c));
      if (a != b) ++bucket_start_[std::min(a, b) + 1];
    }
    std::partial_sum(bucket_start_.begin(), bucket_start_.end(),
                     bucket_start_.begin());
    half_edges_.resize(bucket_start_.back());
    std::vector<uint32_t> fill(bucket_start_.begin(), bucket_start_.end() - 1);
    for (uint32_t c = 0; c < corners; ++c) {
      uint32_t a = VertexAt(c), b = VertexAt(NextCorner(c));
      if (a == b) continue;
      half_edges_[fill[std::min(a, b)]++] = {std::max(a, b), c};
    }
    for (size_t v = 0; v < vertex_count_; ++v) {
      std::sort(half_edges_.begin() + bucket_start_[v],
                half_edges_.begin() + bucket_start_[v + 1],
                [](const HalfEdge& x, const HalfEdge& y) {
                  return x.other != y.other ? x.other < y.other
                                            : x.corner < y.corner;
                });
    }
  }

  // The corner of half-edge `h`'s face that holds vertex `v` of the edge.
  uint32_t CornerOf(const HalfEdge& h, uint32_t v) const {
    return VertexAt(h.corner) == v ? h.corner : NextCorner(h.corner);
  }

  void ScanEdges() {
    for (uint32_t a = 0; a < vertex_count_; ++a) {
      size_t i = bucket_start_[a];
      const size_t end = bucket_start_[a + 1];
      while (i < end) {
        const uint32_t b = half_edges_[i].other;
        size_t j = i + 1;
        while (j < end && half_edges_[j].other == b) ++j;
        ClassifyEdge(a, b, i, j);
        i = j;
      }
    }
  }

  // Half-edges [first, last) all lie on the edge {a, b}, a < b.
  void ClassifyEdge(uint32_t a, uint32_t b, size_t first, size_t last) {
    ++stats_.edges;
    const size_t n = last - first;
    if (n == 1) {
      ++stats_.boundary_edges;
      boundary_graph_.Union(a, b);
      on_boundary_[a] = on_boundary_[b] = true;
    } else if (n > 2) {
      ++stats_.non_manifold_edges;
    } else if (VertexAt(half_edges_[first].corner) ==
               VertexAt(half_edges_[first + 1].corner)) {
      ++stats_.inconsistently_oriented_edges;  // both run a->b, or both b->a
    }
    // Faces across the edge belong to the same fan at a and at b.
    for (size_t k = first + 1; k < last; ++k) {
      fans_.Union(CornerOf(half_edges_[first], a), CornerOf(half_edges_[k], a));
      fans_.Union(CornerOf(half_edges_[first], b), CornerOf(half_edges_[k], b));
    }
  }

  void CountFansAndComponents() {
    std::vector<uint32_t> fan_count(vertex_count_, 0);
    const uint32_t corners = static_cast<uint32_t>(3 * mesh_.faces.size());
    for (uint32_t c = 0; c < corners; ++c) {
      if (fans_.Find(c) == c) ++fan_count[VertexAt(c)];
    }
    for (const Face& f : mesh_.faces) {
      components_.Union(f[0], f[1]);
      components_.Union(f[0], f[2]);
    }
    for (uint32_t v = 0; v < vertex_count_; ++v) {
      if (fan_count[v] > 1) ++stats_.non_manifold_vertices;
      if (referenced_[v] && components_.Find(v) == v) ++stats_.components;
      if (on_boundary_[v] && boundary_graph_.Find(v) == v) {
        ++stats_.boundary_loops;
      }
    }
  }

  const TriMesh& mesh_;
  const size_t vertex_count_;
  MeshStats stats_;
  std::vector<bool> referenced_;
  std::vector<bool> on_boundary_;
  std::vector<uint32_t> bucket_start_;
  std::vector<HalfEdge> half_edges_;
  UnionFind fans_;            // over face corners
  UnionFind boundary_graph_;  // over vertices, joined by boundary edges
  UnionFind components_;      // over vertices, joined by faces
};

}  // namespace

MeshStats ComputeStats(const TriMesh& mesh) {
  return StatsBuilder(mesh).Build();
}

}  // namespace meshwave
