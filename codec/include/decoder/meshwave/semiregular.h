// Semi-regular meshes: a base mesh M^0 refined J times by 1-to-4 splits.
//
// Canonical numbering (derived from M^0 alone, so only M^0 and J travel):
// - Vertices are level-ordered: [0, V_0) are the base vertices, and the odd
//   vertices created by splitting the edges of M^j are [V_j, V_j + E_j), in
//   the order of the edges of M^j, so V_{j+1} = V_j + E_j.
// - Edges of M^0 are numbered by walking faces in order and their corners
//   0-1, 1-2, 2-0, the first time each edge is met; each edge runs from its
//   lower to its higher vertex index.
// - Edges of M^{j+1}: first the two halves of every edge e of M^j (2e runs
//   from e's start to its midpoint, 2e+1 from the midpoint to e's end), then
//   for every face f of M^j the three inner edges 2E_j + 3f + i, inner edge i
//   being parallel to edge i (corner i -> i+1) of f. Every child edge runs in
//   the direction of its parent edge, so tangent frames of parent and child
//   agree (3xC's sign contexts rely on it).
// - Face f = (A, B, C) of M^j has children 4f..4f+3 = (A, mAB, mCA),
//   (B, mBC, mAB), (C, mCA, mBC), (mAB, mBC, mCA).
#ifndef MESHWAVE_SEMIREGULAR_H_
#define MESHWAVE_SEMIREGULAR_H_

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

using Edge = std::array<uint32_t, 2>;  // oriented: [0] -> [1]

// The connectivity of every level of a semi-regular mesh; immutable.
class SemiRegularHierarchy {
 public:
  // Builds J levels over a base mesh with `base_vertex_count` vertices.
  // The base must be an oriented manifold triangle mesh (boundaries allowed)
  // using every vertex; otherwise a kNotManifold/kInvalidArgument error says
  // which vertex or edge is at fault. J is at most 12 and the finest level
  // at most 2^27 faces.
  static Result<std::shared_ptr<const SemiRegularHierarchy>> Build(
      uint32_t base_vertex_count, std::vector<Face> base_faces, int levels);

  int levels() const { return static_cast<int>(faces_.size()) - 1; }
  // V_j for j in [0, J].
  uint32_t vertex_count(int j) const { return vertex_counts_[j]; }
  // Faces of M^j, j in [0, J].
  const std::vector<Face>& faces(int j) const { return faces_[j]; }
  // Edges of M^j for j in [0, J): edge k is split by vertex V_j + k, and is
  // the position of coefficient k in subband d^j.
  const std::vector<Edge>& edges(int j) const { return edges_[j]; }
  // face_edges(j)[f][i] = index of the edge from corner i to corner i+1.
  const std::vector<std::array<uint32_t, 3>>& face_edges(int j) const {
    return face_edges_[j];
  }
  // Number of coefficients of d^j (= E_j).
  size_t subband_size(int j) const { return edges_[j].size(); }

  // Parent of coefficient k of d^j (j >= 1), an index into d^{j-1}.
  uint32_t Parent(int j, uint32_t k) const;
  // Children of coefficient k of d^j (j + 1 < J) in d^{j+1}: the two halves
  // and one inner edge per adjacent face (4 inside, 3 on a boundary edge).
  // Returns how many were written to `out`.
  int Children(int j, uint32_t k, std::array<uint32_t, 4>& out) const;

  // The faces adjacent to each edge of M^j: {face, face or kNone}.
  static constexpr uint32_t kNone = 0xffffffffu;
  const std::vector<std::array<uint32_t, 2>>& edge_faces(int j) const {
    return edge_faces_[j];
  }

 private:
  SemiRegularHierarchy() = default;
  // Splits the finest level once; without `split_edges` only its faces are
  // built (the last level, whose edges nothing reads).
  void AddLevel(bool split_edges);

  std::vector<uint32_t> vertex_counts_;
  std::vector<std::vector<Face>> faces_;
  std::vector<std::vector<Edge>> edges_;
  std::vector<std::vector<std::array<uint32_t, 3>>> face_edges_;
  std::vector<std::vector<std::array<uint32_t, 2>>> edge_faces_;
};

// A semi-regular mesh: hierarchy plus the positions of the finest level in
// canonical order (the first V_j of them are the vertices of M^j).
struct SemiRegularMesh {
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  std::vector<Vec3> positions;

  int levels() const { return hierarchy->levels(); }
  // M^j as a TriMesh (the first V_j positions, faces of level j).
  TriMesh Level(int j) const;
  TriMesh Finest() const { return Level(levels()); }
};

}  // namespace meshwave

#endif  // MESHWAVE_SEMIREGULAR_H_
