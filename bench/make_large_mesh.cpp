// make_large_mesh: a large irregular mesh made reproducibly from a small
// one, for measuring ingest at scale (bench/ingest_scale.sh). The input is
// Loop-subdivided as often as stays under the face count asked for, then
// randomly chosen edges are split at their midpoints until it is reached,
// a fraction of the edges is flipped where the flip keeps the surface's
// orientation, and every vertex moves by a small random offset. Splits and
// flips break the subdivision connectivity, so the result is not
// semi-regular and ingest remeshes it as it would a scan. The same input,
// count and seed give the same bytes (a fixed generator, no
// std::*_distribution, whose output differs between libraries).
//
//   make_large_mesh IN OUT.ply --faces N [--seed 1] [--flip-fraction 0.05]
//                   [--jitter 0.05]
//
// --jitter is in mean edge lengths of the result.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/edge_key.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace {

using meshwave::Face;
using meshwave::TriMesh;
using meshwave::Vec3;

// splitmix64: small, fast and the same everywhere.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t Next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double Unit() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  uint64_t state_;
};

// The mesh's edges, each with the faces on either side (the second is
// kNone on a boundary; an edge of more than two faces is left out).
constexpr uint32_t kNone = ~0u;
struct Edge {
  uint32_t a, b;           // a < b
  uint32_t face[2];
};

std::vector<Edge> Edges(const TriMesh& mesh) {
  std::vector<std::pair<uint64_t, uint32_t>> halves;
  halves.reserve(mesh.faces.size() * 3);
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      halves.emplace_back(meshwave::EdgeKey(mesh.faces[f][c], mesh.faces[f][(c + 1) % 3]), f);
    }
  }
  std::sort(halves.begin(), halves.end());
  std::vector<Edge> edges;
  edges.reserve(halves.size() / 2 + 1);
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].first == halves[i].first) ++j;
    if (j - i <= 2) {
      const uint64_t key = halves[i].first;
      edges.push_back({static_cast<uint32_t>(key >> 32), static_cast<uint32_t>(key),
                       {halves[i].second, j - i == 2 ? halves[i + 1].second : kNone}});
    }
    i = j;
  }
  return edges;
}

// The corner of face f opposite the edge {a, b}.
int Opposite(const Face& f, uint32_t a, uint32_t b) {
  for (int c = 0; c < 3; ++c) {
    if (f[c] != a && f[c] != b) return c;
  }
  return -1;
}

// Splits randomly chosen edges, no two of one face in a round, until the
// mesh has `target` faces.
void SplitUntil(TriMesh& mesh, size_t target, Random& random) {
  while (mesh.faces.size() < target) {
    std::vector<Edge> edges = Edges(mesh);
    std::vector<uint8_t> used(mesh.faces.size(), 0);
    for (size_t k = 0; k < edges.size() && mesh.faces.size() < target; ++k) {
      const Edge& e = edges[random.Next() % edges.size()];
      if (used[e.face[0]] || (e.face[1] != kNone && used[e.face[1]])) continue;
      const auto m = static_cast<uint32_t>(mesh.positions.size());
      mesh.positions.push_back(0.5 * (mesh.positions[e.a] + mesh.positions[e.b]));
      for (uint32_t f : e.face) {
        if (f == kNone) continue;
        used[f] = 1;
        Face& face = mesh.faces[f];
        const int o = Opposite(face, e.a, e.b);
        // face = (o, p, q) with p -> q along the edge: (o, p, m) and (o, m, q).
        const Face rotated = {face[o], face[(o + 1) % 3], face[(o + 2) % 3]};
        face = {rotated[0], rotated[1], m};
        mesh.faces.push_back({rotated[0], m, rotated[2]});
        used.push_back(1);
      }
    }
  }
}

// Flips a fraction of the interior edges where the flipped pair faces the
// way the old pair did and adds no edge that exists.
size_t Flip(TriMesh& mesh, double fraction, Random& random) {
  std::vector<Edge> edges = Edges(mesh);
  std::vector<uint64_t> existing;
  existing.reserve(edges.size());
  for (const Edge& e : edges) existing.push_back(meshwave::EdgeKey(e.a, e.b));
  std::sort(existing.begin(), existing.end());
  std::vector<uint8_t> used(mesh.faces.size(), 0);
  std::unordered_set<uint64_t> made;
  const auto wanted = static_cast<size_t>(fraction * static_cast<double>(edges.size()));
  size_t flipped = 0;
  for (size_t k = 0; k < 4 * wanted && flipped < wanted; ++k) {
    const Edge& e = edges[random.Next() % edges.size()];
    if (e.face[1] == kNone || used[e.face[0]] || used[e.face[1]]) continue;
    Face& f0 = mesh.faces[e.face[0]];
    Face& f1 = mesh.faces[e.face[1]];
    const uint32_t c = f0[Opposite(f0, e.a, e.b)], d = f1[Opposite(f1, e.a, e.b)];
    const uint64_t key = meshwave::EdgeKey(c, d);
    // Neither an edge of the mesh nor one an earlier flip made.
    if (c == d || std::binary_search(existing.begin(), existing.end(), key) || made.count(key)) {
      continue;
    }
    // f0 = (c, p, q): the new faces (c, p, d) and (c, d, q).
    const int o = Opposite(f0, e.a, e.b);
    const uint32_t p = f0[(o + 1) % 3], q = f0[(o + 2) % 3];
    const auto& x = mesh.positions;
    const Vec3 before = (x[p] - x[c]).cross(x[q] - x[c]) + (x[q] - x[d]).cross(x[p] - x[d]);
    const Vec3 n0 = (x[p] - x[c]).cross(x[d] - x[c]), n1 = (x[d] - x[c]).cross(x[q] - x[c]);
    if (n0.dot(before) <= 0 || n1.dot(before) <= 0) continue;
    f0 = {c, p, d};
    f1 = {c, d, q};
    made.insert(key);
    used[e.face[0]] = used[e.face[1]] = 1;
    ++flipped;
  }
  return flipped;
}

int Usage() {
  std::fprintf(stderr,
               "usage: make_large_mesh IN OUT.ply --faces N [--seed S] [--flip-fraction F] "
               "[--jitter J]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) return Usage();
  const std::string in = argv[1], out = argv[2];
  size_t target = 0;
  uint64_t seed = 1;
  double flip_fraction = 0.05, jitter = 0.05;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--faces") target = std::stoull(value);
    else if (flag == "--seed") seed = std::stoull(value);
    else if (flag == "--flip-fraction") flip_fraction = std::stod(value);
    else if (flag == "--jitter") jitter = std::stod(value);
    else return Usage();
  }
  if (target == 0) return Usage();
  auto read = meshwave::ReadMesh(in);
  if (!read.ok()) {
    std::fprintf(stderr, "make_large_mesh: %s\n", read.status().ToString().c_str());
    return 1;
  }
  TriMesh mesh = std::move(*read);
  meshwave::CleanMesh(mesh);
  int levels = 0;
  while (mesh.faces.size() << (2 * (levels + 1)) <= target) ++levels;
  if (levels > 0) {
    auto sub = meshwave::Subdivide(mesh, levels, meshwave::SubdivisionScheme::kLoop);
    if (!sub.ok()) {
      std::fprintf(stderr, "make_large_mesh: %s\n", sub.status().ToString().c_str());
      return 1;
    }
    mesh = sub->Finest();
  }
  Random random(seed);
  SplitUntil(mesh, target, random);
  const size_t flipped = Flip(mesh, flip_fraction, random);
  double length = 0;
  for (const Face& f : mesh.faces) length += (mesh.positions[f[0]] - mesh.positions[f[1]]).norm();
  const double step = jitter * length / static_cast<double>(mesh.faces.size());
  for (Vec3& p : mesh.positions) {
    p += step * Vec3(2 * random.Unit() - 1, 2 * random.Unit() - 1, 2 * random.Unit() - 1);
  }
  if (auto s = meshwave::WriteMesh(mesh, out); !s.ok()) {
    std::fprintf(stderr, "make_large_mesh: %s\n", s.ToString().c_str());
    return 1;
  }
  std::printf("%s: %zu vertices, %zu faces (%d Loop levels, %zu edges flipped, seed %llu)\n",
              out.c_str(), mesh.positions.size(), mesh.faces.size(), levels, flipped,
              static_cast<unsigned long long>(seed));
  return 0;
}
