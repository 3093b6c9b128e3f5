// RepairManifold: glue faces along edges shared by exactly two faces, orient
// the glued pieces consistently, and give every fan of faces around a vertex
// its own vertex.
#include "remesh/manifold_repair.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "core/edge_key.h"
#include "core/parallel_for.h"
#include "remesh/union_find.h"

namespace meshwave::remesh {
namespace {

constexpr uint32_t kUnglued = 0xffffffffu;

uint32_t CornerOf(const Face& f, uint32_t v) {
  return f[0] == v ? 0u : (f[1] == v ? 1u : 2u);
}

Vec3 UnitNormal(const TriMesh& mesh, uint32_t f) {
  const Face& t = mesh.faces[f];
  const Vec3 n = (mesh.positions[t[1]] - mesh.positions[t[0]])
                     .cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
  const double length = n.norm();
  return length > 0 ? Vec3(n / length) : Vec3(Vec3::Zero());
}

// glue[3f + i] is the half-edge (edge i of face f, corner i -> i+1) glued to
// it, or kUnglued. An edge of two faces is glued; of an edge with more, the
// two faces that run it in opposite directions and continue each other
// most smoothly (largest dot product of normals) are glued and the others
// cut off: a fin hanging off a surface leaves the surface whole.
std::vector<uint32_t> PairHalfEdges(const TriMesh& mesh,
                                    size_t* non_manifold_edges, int threads) {
  const std::vector<Face>& faces = mesh.faces;
  const size_t n = faces.size() * 3;
  std::vector<std::pair<uint64_t, uint32_t>> keyed(n);
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      keyed[3 * f + i] = {EdgeKey(faces[f][i], faces[f][(i + 1) % 3]),
                          static_cast<uint32_t>(3 * f + i)};
    }
  }
  ParallelSort(keyed.begin(), keyed.end(), threads);
  std::vector<uint32_t> glue(n, kUnglued);
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && keyed[j].first == keyed[i].first) ++j;
    if (j - i == 2) {
      glue[keyed[i].second] = keyed[i + 1].second;
      glue[keyed[i + 1].second] = keyed[i].second;
    } else if (j - i > 2) {
      ++*non_manifold_edges;
      double best = -2;
      size_t pick_a = 0, pick_b = 0;
      for (size_t a = i; a < j; ++a) {
        for (size_t b = a + 1; b < j; ++b) {
          const uint32_t ha = keyed[a].second, hb = keyed[b].second;
          if (faces[ha / 3][ha % 3] == faces[hb / 3][hb % 3]) continue;
          const double agreement =
              UnitNormal(mesh, ha / 3).dot(UnitNormal(mesh, hb / 3));
          if (agreement > best) {
            best = agreement;
            pick_a = a;
            pick_b = b;
          }
        }
      }
      if (best > -2) {
        glue[keyed[pick_a].second] = keyed[pick_b].second;
        glue[keyed[pick_b].second] = keyed[pick_a].second;
      }
    }
    i = j;
  }
  return glue;
}

// Chooses a flip per face so that glued neighbours run their shared edge in
// opposite directions; cuts glues that contradict (non-orientable pieces).
// Each piece keeps the orientation of the majority of its faces.
std::vector<uint8_t> Orient(const std::vector<Face>& faces,
                            std::vector<uint32_t>& glue, RepairReport& report) {
  const size_t n = faces.size();
  std::vector<uint8_t> flip(n, 0), seen(n, 0);
  std::vector<uint32_t> queue, members;
  for (uint32_t h = 0; h < glue.size(); ++h) {
    const uint32_t g = glue[h];
    if (g != kUnglued && h < g && faces[h / 3][h % 3] == faces[g / 3][g % 3]) {
      ++report.misoriented_edges;
    }
  }
  for (uint32_t seed = 0; seed < n; ++seed) {
    if (seen[seed]) continue;
    seen[seed] = 1;
    queue.assign(1, seed);
    members.clear();
    for (size_t head = 0; head < queue.size(); ++head) {
      const uint32_t f = queue[head];
      members.push_back(f);
      for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t h = 3 * f + i;
        const uint32_t gh = glue[h];
        if (gh == kUnglued) continue;
        const uint32_t g = gh / 3;
        const bool same_direction = faces[f][i] == faces[g][gh % 3];
        const uint8_t want = flip[f] ^ static_cast<uint8_t>(same_direction);
        if (!seen[g]) {
          seen[g] = 1;
          flip[g] = want;
          queue.push_back(g);
        } else if (flip[g] != want) {
          glue[h] = glue[gh] = kUnglued;
          ++report.non_orientable_cuts;
        }
      }
    }
    size_t flipped = 0;
    for (uint32_t f : members) flipped += flip[f];
    if (2 * flipped > members.size()) {
      for (uint32_t f : members) flip[f] ^= 1;
    }
  }
  return flip;
}

// Faces that still share a directed edge, or an edge with more than two
// faces, after the split (possible only when fans reconnect elsewhere).
std::vector<uint32_t> FacesOnBadEdges(const std::vector<Face>& faces, int threads) {
  std::vector<std::pair<uint64_t, uint32_t>> keyed(faces.size() * 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int i = 0; i < 3; ++i) {
      keyed[3 * f + i] = {EdgeKey(faces[f][i], faces[f][(i + 1) % 3]),
                          static_cast<uint32_t>(3 * f + i)};
    }
  }
  ParallelSort(keyed.begin(), keyed.end(), threads);
  std::vector<uint32_t> bad;
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i + 1;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    bool broken = j - i > 2;
    if (j - i == 2) {
      const uint32_t h = keyed[i].second, g = keyed[i + 1].second;
      broken = faces[h / 3][h % 3] == faces[g / 3][g % 3];
    }
    if (broken) {
      for (size_t k = i; k < j; ++k) bad.push_back(keyed[k].second / 3);
    }
    i = j;
  }
  return bad;
}

}  // namespace

RepairReport RepairManifold(TriMesh& mesh, int threads) {
  RepairReport report;
  const size_t vertex_count = mesh.positions.size();
  for (const Face& f : mesh.faces) {
    assert(f[0] < vertex_count && f[1] < vertex_count && f[2] < vertex_count);
    assert(f[0] != f[1] && f[1] != f[2] && f[2] != f[0]);
    (void)f;
  }
  std::vector<uint32_t> glue = PairHalfEdges(mesh, &report.non_manifold_edges, threads);
  const std::vector<uint8_t> flip = Orient(mesh.faces, glue, report);
  // Glue refers to corners of the unflipped faces; keep those for lookups.
  const std::vector<Face> original = mesh.faces;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (flip[f]) {
      std::swap(mesh.faces[f][1], mesh.faces[f][2]);
      ++report.reoriented_faces;
    }
  }

  const size_t corners = mesh.faces.size() * 3;
  std::vector<Face> out(mesh.faces.size());
  while (true) {
    // Corners of one vertex joined across glued edges form one fan.
    UnionFind fans(corners);
    for (uint32_t h = 0; h < corners; ++h) {
      const uint32_t g = glue[h];
      if (g == kUnglued || g < h) continue;
      const uint32_t f = h / 3, k = g / 3;
      for (const uint32_t v :
           {original[f][h % 3], original[f][(h % 3 + 1) % 3]}) {
        fans.Union(3 * f + CornerOf(mesh.faces[f], v),
                   3 * k + CornerOf(mesh.faces[k], v));
      }
    }
    // The first fan met keeps the vertex; later fans get copies.
    mesh.positions.resize(vertex_count);
    std::vector<uint32_t> id_of_root(corners, kUnglued);
    std::vector<uint8_t> fans_of_vertex(vertex_count, 0);
    for (uint32_t c = 0; c < corners; ++c) {
      const uint32_t root = fans.Find(c);
      const uint32_t v = mesh.faces[c / 3][c % 3];
      if (id_of_root[root] == kUnglued) {
        if (fans_of_vertex[v] == 0) {
          id_of_root[root] = v;
        } else {
          id_of_root[root] = static_cast<uint32_t>(mesh.positions.size());
          mesh.positions.push_back(mesh.positions[v]);
        }
        fans_of_vertex[v] =
            static_cast<uint8_t>(std::min(fans_of_vertex[v] + 1, 255));
      }
      out[c / 3][c % 3] = id_of_root[root];
    }
    const std::vector<uint32_t> bad = FacesOnBadEdges(out, threads);
    if (bad.empty()) {
      report.added_vertices = mesh.positions.size() - vertex_count;
      report.non_manifold_vertices = static_cast<size_t>(
          std::count_if(fans_of_vertex.begin(), fans_of_vertex.end(),
                        [](uint8_t n) { return n > 1; }));
      break;
    }
    // Detach the offending faces from everything; every round removes at
    // least one glue, so this ends (at worst with loose triangles).
    for (uint32_t f : bad) {
      for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t g = glue[3 * f + i];
        if (g == kUnglued) continue;
        glue[g] = glue[3 * f + i] = kUnglued;
        ++report.fallback_cuts;
      }
    }
  }
  mesh.faces = std::move(out);
  return report;
}

}  // namespace meshwave::remesh
