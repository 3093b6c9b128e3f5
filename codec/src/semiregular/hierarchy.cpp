// SemiRegularHierarchy: the canonical connectivity of every level, derived
// from the base faces by structural rules (no hashing past level 0), so the
// encoder and the decoder build identical tables.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/edge_index_table.h"
#include "meshwave/semiregular.h"
#include "meshwave/stream_limits.h"
#include "semiregular/vertex_rings.h"

namespace meshwave {
namespace {

constexpr double kMaxFinestFaces = 134217728.0;  // 2^27

}  // namespace

Result<std::shared_ptr<const SemiRegularHierarchy>> SemiRegularHierarchy::Build(
    uint32_t base_vertex_count, std::vector<Face> base_faces, int levels) {
  if (levels < 0 || levels > kMaxStreamLevels) {
    return InvalidArgument("levels must be in [0, " +
                           std::to_string(kMaxStreamLevels) + "], got " +
                           std::to_string(levels));
  }
  if (base_faces.empty()) return InvalidArgument("base mesh has no faces");
  auto rings = VertexRings::Build(base_vertex_count, base_faces);
  if (!rings.ok()) return rings.status().WithContext("base mesh");
  // Cap the size before allocating: a small base with many levels (from an
  // untrusted stream, say) must not exhaust memory. 2^27 faces is about 67 M
  // vertices and 5 GB of tables, far beyond any mesh we stream.
  {
    const double finest_faces =
        static_cast<double>(base_faces.size()) * std::pow(4.0, levels);
    if (finest_faces > kMaxFinestFaces) {
      return InvalidArgument(
          "a " + std::to_string(levels) + "-level hierarchy over " +
          std::to_string(base_faces.size()) + " base faces would have " +
          std::to_string(static_cast<uint64_t>(finest_faces)) +
          " faces, more than the limit of 2^27");
    }
  }

  std::shared_ptr<SemiRegularHierarchy> h(new SemiRegularHierarchy());
  h->vertex_counts_.push_back(base_vertex_count);
  // Level-0 edges: first meeting in face/corner order, lower -> higher index.
  std::vector<Edge> edges;
  std::vector<std::array<uint32_t, 3>> face_edges(base_faces.size());
  EdgeIndexTable index(base_faces.size() * 3 / 2 + 1);
  edges.reserve(base_faces.size() * 3 / 2 + 1);  // a closed mesh's count
  for (size_t f = 0; f < base_faces.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = base_faces[f][i], b = base_faces[f][(i + 1) % 3];
      auto [id, inserted] = index.Emplace(a, b, static_cast<uint32_t>(edges.size()));
      if (inserted) edges.push_back({std::min(a, b), std::max(a, b)});
      face_edges[f][i] = id;
    }
  }
  h->faces_.push_back(std::move(base_faces));
  h->edges_.push_back(std::move(edges));
  h->face_edges_.push_back(std::move(face_edges));
  // The finest level is not split (no d^J): its edge tables, the largest of
  // all, are never built.
  for (int j = 0; j < levels; ++j) h->AddLevel(/*split_edges=*/j + 1 < levels);

  // Faces adjacent to each split edge, for stencils and frames.
  for (int j = 0; j < levels; ++j) {
    std::vector<std::array<uint32_t, 2>> ef(h->edges_[j].size(),
                                            {kNone, kNone});
    const auto& fe = h->face_edges_[j];
    for (uint32_t f = 0; f < fe.size(); ++f) {
      for (int i = 0; i < 3; ++i) {
        auto& slot = ef[fe[f][i]];
        (slot[0] == kNone ? slot[0] : slot[1]) = f;
      }
    }
    h->edge_faces_.push_back(std::move(ef));
  }
  return std::shared_ptr<const SemiRegularHierarchy>(std::move(h));
}

void SemiRegularHierarchy::AddLevel(bool split_edges) {
  const int j = static_cast<int>(faces_.size()) - 1;
  const uint32_t vj = vertex_counts_[j];
  const auto& faces = faces_[j];
  const auto& edges = edges_[j];
  const auto& face_edges = face_edges_[j];
  const uint32_t num_edges = static_cast<uint32_t>(edges.size());
  vertex_counts_.push_back(vj + num_edges);

  std::vector<Face> child_faces(4 * faces.size());
  std::vector<Edge> child_edges;
  std::vector<std::array<uint32_t, 3>> child_face_edges;
  if (split_edges) {
    child_edges.resize(2 * size_t{num_edges} + 3 * faces.size());
    child_face_edges.resize(4 * faces.size());
    for (uint32_t e = 0; e < num_edges; ++e) {
      const uint32_t m = vj + e;
      child_edges[2 * e] = {edges[e][0], m};
      child_edges[2 * e + 1] = {m, edges[e][1]};
    }
  }
  for (uint32_t f = 0; f < faces.size(); ++f) {
    const Face& t = faces[f];
    const auto& fe = face_edges[f];
    uint32_t mid[3];  // mid[i] splits edge i (corner i -> i+1)
    for (int i = 0; i < 3; ++i) mid[i] = vj + fe[i];
    // Corner faces (t[i], mid[i], mid[i+2]) and the central face.
    for (int i = 0; i < 3; ++i) child_faces[4 * f + i] = {t[i], mid[i], mid[(i + 2) % 3]};
    child_faces[4 * f + 3] = {mid[0], mid[1], mid[2]};
    if (!split_edges) continue;
    // Half of edge i that touches corner c (c is i or i+1).
    auto half = [&](int i, uint32_t corner) {
      return 2 * fe[i] + (edges[fe[i]][0] == corner ? 0u : 1u);
    };
    const uint32_t inner = 2 * num_edges + 3 * f;
    // Inner edge i joins the midpoints of the two other edges of f and is
    // parallel to edge i; orient it like edge i.
    for (int i = 0; i < 3; ++i) {
      const uint32_t from = mid[(i + 2) % 3], to = mid[(i + 1) % 3];
      const bool same = edges[fe[i]][0] == t[i];
      child_edges[inner + i] = same ? Edge{from, to} : Edge{to, from};
      child_face_edges[4 * f + i] = {half(i, t[i]), inner + (i + 1) % 3,
                                     half((i + 2) % 3, t[i])};
    }
    child_face_edges[4 * f + 3] = {inner + 2, inner + 0, inner + 1};
  }
  faces_.push_back(std::move(child_faces));
  if (split_edges) {
    edges_.push_back(std::move(child_edges));
    face_edges_.push_back(std::move(child_face_edges));
  }
}

uint32_t SemiRegularHierarchy::Parent(int j, uint32_t k) const {
  const uint32_t num_parent_edges =
      static_cast<uint32_t>(edges_[j - 1].size());
  if (k < 2 * num_parent_edges) return k / 2;
  const uint32_t inner = k - 2 * num_parent_edges;
  return face_edges_[j - 1][inner / 3][inner % 3];
}

int SemiRegularHierarchy::Children(int j, uint32_t k,
                                   std::array<uint32_t, 4>& out) const {
  int n = 0;
  out[n++] = 2 * k;
  out[n++] = 2 * k + 1;
  const uint32_t base = 2 * static_cast<uint32_t>(edges_[j].size());
  for (uint32_t f : edge_faces_[j][k]) {
    if (f == kNone) continue;
    const auto& fe = face_edges_[j][f];
    for (uint32_t i = 0; i < 3; ++i) {
      if (fe[i] == k) out[n++] = base + 3 * f + i;
    }
  }
  return n;
}

TriMesh SemiRegularMesh::Level(int j) const {
  TriMesh m;
  m.positions.assign(positions.begin(),
                     positions.begin() + hierarchy->vertex_count(j));
  m.faces = hierarchy->faces(j);
  return m;
}

}  // namespace meshwave
