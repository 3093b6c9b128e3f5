// DetectSemiRegular: undo 1-to-4 splits level by level by labelling every
// vertex even (kept) or odd (created on an edge), docs/CODEC.md "Detection", then
// renumber the recovered hierarchy canonically.
#include <algorithm>
#include <deque>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "core/edge_key.h"
#include "core/hash_mix.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "semiregular/vertex_rings.h"

namespace meshwave {
namespace {

constexpr uint32_t kUnset = 0xffffffffu;
enum Parity : uint8_t { kUnknown = 0, kEven = 1, kOdd = 2 };

// A face as a key that ignores rotation but keeps orientation.
struct FaceKey {
  uint32_t a, b, c;
  explicit FaceKey(const Face& f) {
    int m = 0;
    if (f[1] < f[m]) m = 1;
    if (f[2] < f[m]) m = 2;
    a = f[m];
    b = f[(m + 1) % 3];
    c = f[(m + 2) % 3];
  }
  bool operator==(const FaceKey&) const = default;
};
struct FaceKeyHash {
  size_t operator()(const FaceKey& k) const { return HashTriple(k.a, k.b, k.c); }
};

// One undone level, in the local vertex numbering of the finer mesh.
struct UndoneLevel {
  std::vector<Face> coarse_faces;
  std::unordered_map<uint64_t, uint32_t> edge_to_odd;
};

class LevelUndoer {
 public:
  LevelUndoer(const VertexRings& rings, const std::vector<Face>& faces)
      : rings_(rings),
        faces_(faces),
        n_(rings.vertex_count()),
        label_(n_, kUnknown),
        known_even_(n_, kUnset) {}

  // Undoes one level or says why it cannot.
  Result<UndoneLevel> Run() {
    // Components of the vertex graph, and the faces of each.
    std::vector<uint32_t> component(n_, kUnset);
    std::vector<std::vector<uint32_t>> members;
    for (uint32_t s = 0; s < n_; ++s) {
      if (component[s] != kUnset) continue;
      const uint32_t c = static_cast<uint32_t>(members.size());
      members.emplace_back();
      std::vector<uint32_t> stack{s};
      component[s] = c;
      while (!stack.empty()) {
        const uint32_t v = stack.back();
        stack.pop_back();
        members[c].push_back(v);
        for (uint32_t u : rings_.Ring(v)) {
          if (component[u] == kUnset) {
            component[u] = c;
            stack.push_back(u);
          }
        }
      }
    }
    std::vector<std::vector<uint32_t>> component_faces(members.size());
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      component_faces[component[faces_[f][0]]].push_back(f);
    }
    UndoneLevel out;
    for (size_t c = 0; c < members.size(); ++c) {
      auto status = UndoComponent(members[c], component_faces[c], out);
      if (!status.ok()) {
        if (members.size() == 1) return status;
        return status.WithContext("component " + std::to_string(c) + " of " +
                                  std::to_string(members.size()));
      }
    }
    return out;
  }

 private:
  bool Extraordinary(uint32_t v) const {
    return rings_.Valence(v) != (rings_.IsBoundary(v) ? 4u : 6u);
  }

  Status UndoComponent(const std::vector<uint32_t>& vertices,
                       const std::vector<uint32_t>& faces, UndoneLevel& out) {
    // A vertex of unusual valence was in M^0, so it is even; a component
    // without one (a torus, say) tries a vertex and its ring as seeds.
    std::vector<uint32_t> seeds;
    for (uint32_t v : vertices) {
      if (Extraordinary(v)) {
        seeds.push_back(v);
        break;
      }
    }
    if (seeds.empty()) {
      seeds.push_back(vertices.front());
      for (uint32_t u : rings_.Ring(vertices.front())) seeds.push_back(u);
    }
    Status last;
    for (uint32_t seed : seeds) {
      for (uint32_t v : vertices) {
        label_[v] = kUnknown;
        known_even_[v] = kUnset;
      }
      last = LabelFrom(seed);
      if (last.ok()) {
        UndoneLevel attempt;
        last = Validate(vertices, faces, attempt);
        if (last.ok()) {
          out.coarse_faces.insert(out.coarse_faces.end(),
                                  attempt.coarse_faces.begin(),
                                  attempt.coarse_faces.end());
          out.edge_to_odd.merge(attempt.edge_to_odd);
          return Status::Ok();
        }
      }
    }
    return last;
  }

  Status Conflict(uint32_t v) const {
    return Status(StatusCode::kNotSemiRegular,
                  "vertex " + std::to_string(v) +
                      " cannot be labelled as kept or inserted: its "
                      "neighbourhood is not that of a 1-to-4 split");
  }

  // Sets v's label; false on a contradiction.
  bool Assign(uint32_t v, Parity l, std::deque<uint32_t>& queue) {
    if (label_[v] == l) return true;
    if (label_[v] != kUnknown) return false;
    label_[v] = l;
    queue.push_back(v);
    return true;
  }

  Status LabelFrom(uint32_t seed) {
    std::deque<uint32_t> queue;
    label_[seed] = kEven;
    queue.push_back(seed);
    while (!queue.empty()) {
      const uint32_t v = queue.front();
      queue.pop_front();
      auto ring = rings_.Ring(v);
      if (label_[v] == kEven) {
        for (uint32_t u : ring) {
          if (!Assign(u, kOdd, queue)) return Conflict(u);
          if (known_even_[u] == kUnset) {
            known_even_[u] = v;
            queue.push_back(u);  // now it can be processed
          }
        }
        continue;
      }
      // Odd: an inserted vertex has valence 6 (4 on a boundary) and its two
      // parents sit opposite each other on its ring.
      const size_t k = ring.size();
      if (rings_.IsBoundary(v)) {
        if (k != 4) return Conflict(v);
        if (!Assign(ring[0], kEven, queue) || !Assign(ring[3], kEven, queue) ||
            !Assign(ring[1], kOdd, queue) || !Assign(ring[2], kOdd, queue)) {
          return Conflict(v);
        }
        continue;
      }
      if (k != 6) return Conflict(v);
      if (known_even_[v] == kUnset) continue;
      size_t p = 0;
      while (ring[p] != known_even_[v]) ++p;
      for (size_t i = 0; i < 6; ++i) {
        const Parity l = (i == 0 || i == 3) ? kEven : kOdd;
        if (!Assign(ring[(p + i) % 6], l, queue)) return Conflict(v);
      }
    }
    return Status::Ok();
  }

  // The two even neighbours of odd vertex v (its parent edge).
  Edge Parents(uint32_t v) const {
    Edge e{kUnset, kUnset};
    int n = 0;
    for (uint32_t u : rings_.Ring(v)) {
      if (label_[u] == kEven && n < 2) e[n++] = u;
    }
    return e;
  }

  Status Validate(const std::vector<uint32_t>& vertices,
                  const std::vector<uint32_t>& faces, UndoneLevel& out) const {
    std::unordered_map<uint32_t, Edge> parents;
    for (uint32_t v : vertices) {
      if (label_[v] == kUnknown) {
        return Status(StatusCode::kNotSemiRegular,
                      "vertex " + std::to_string(v) + " was not reached");
      }
      if (label_[v] != kOdd) continue;
      const Edge e = Parents(v);
      if (e[1] == kUnset) return Conflict(v);
      if (!out.edge_to_odd.emplace(EdgeKey(e[0], e[1]), v).second) {
        return Status(StatusCode::kNotSemiRegular,
                      "two inserted vertices share the parent edge (" +
                          std::to_string(e[0]) + ", " + std::to_string(e[1]) +
                          ")");
      }
      parents.emplace(v, e);
    }
    auto common = [&](uint32_t x, uint32_t y) {
      const Edge& a = parents.at(x);
      const Edge& b = parents.at(y);
      if (a[0] == b[0] || a[0] == b[1]) return a[0];
      if (a[1] == b[0] || a[1] == b[1]) return a[1];
      return kUnset;
    };
    std::unordered_set<FaceKey, FaceKeyHash> fine;
    fine.reserve(faces.size());
    for (uint32_t f : faces) {
      const Face& t = faces_[f];
      fine.insert(FaceKey(t));
      if (label_[t[0]] != kOdd || label_[t[1]] != kOdd || label_[t[2]] != kOdd) {
        continue;
      }
      const Face coarse{common(t[2], t[0]), common(t[0], t[1]),
                        common(t[1], t[2])};
      if (coarse[0] == kUnset || coarse[1] == kUnset || coarse[2] == kUnset ||
          coarse[0] == coarse[1] || coarse[1] == coarse[2] ||
          coarse[2] == coarse[0]) {
        return Status(StatusCode::kNotSemiRegular,
                      "face " + std::to_string(f) +
                          " looks central but its corners do not span a "
                          "coarse triangle");
      }
      out.coarse_faces.push_back(coarse);
    }
    if (out.coarse_faces.size() * 4 != faces.size()) {
      return Status(StatusCode::kNotSemiRegular,
                    std::to_string(faces.size()) + " faces are not 4 times " +
                        std::to_string(out.coarse_faces.size()) +
                        " central faces");
    }
    // Splitting the coarse faces again must give back exactly these faces.
    for (const Face& c : out.coarse_faces) {
      uint32_t m[3];
      for (int i = 0; i < 3; ++i) {
        auto it = out.edge_to_odd.find(EdgeKey(c[i], c[(i + 1) % 3]));
        if (it == out.edge_to_odd.end()) {
          return Status(StatusCode::kNotSemiRegular,
                        "coarse edge (" + std::to_string(c[i]) + ", " +
                            std::to_string(c[(i + 1) % 3]) +
                            ") has no inserted vertex");
        }
        m[i] = it->second;
      }
      const Face children[4] = {{c[0], m[0], m[2]},
                                {c[1], m[1], m[0]},
                                {c[2], m[2], m[1]},
                                {m[0], m[1], m[2]}};
      for (const Face& child : children) {
        if (!fine.contains(FaceKey(child))) {
          return Status(StatusCode::kNotSemiRegular,
                        "a split of coarse face (" + std::to_string(c[0]) +
                            ", " + std::to_string(c[1]) + ", " +
                            std::to_string(c[2]) +
                            ") is missing from the mesh");
        }
      }
    }
    return Status::Ok();
  }

  const VertexRings& rings_;
  const std::vector<Face>& faces_;
  uint32_t n_;
  std::vector<Parity> label_;
  std::vector<uint32_t> known_even_;
};

// Faces over global ids -> compact local ids (sorted by global id).
struct Compacted {
  std::vector<uint32_t> local_to_global;
  std::vector<Face> faces;
};
Compacted Compact(const std::vector<Face>& faces, size_t id_bound) {
  std::vector<uint32_t> local(id_bound, kUnset);
  Compacted out;
  for (const Face& f : faces) {
    for (uint32_t v : f) local[v] = 0;
  }
  for (size_t v = 0; v < id_bound; ++v) {
    if (local[v] == 0) {
      local[v] = static_cast<uint32_t>(out.local_to_global.size());
      out.local_to_global.push_back(static_cast<uint32_t>(v));
    }
  }
  out.faces.reserve(faces.size());
  for (const Face& f : faces) out.faces.push_back({local[f[0]], local[f[1]], local[f[2]]});
  return out;
}

}  // namespace

Result<DetectedSemiRegular> DetectSemiRegular(const TriMesh& mesh,
                                              const DetectOptions& options) {
  const size_t n = mesh.positions.size();
  if (mesh.faces.empty()) return InvalidArgument("mesh has no faces");
  if (n >= kUnset) return InvalidArgument("mesh has too many vertices");
  {
    auto rings = VertexRings::Build(static_cast<uint32_t>(n), mesh.faces);
    if (!rings.ok()) {
      return Status(StatusCode::kNotSemiRegular,
                    "subdivision connectivity needs a clean manifold mesh: " +
                        rings.status().message());
    }
  }
  // Undo levels; every level is kept in global (input) vertex ids.
  std::vector<UndoneLevel> undone;  // finest first
  std::vector<Face> faces = mesh.faces;
  std::string stop_reason = "reached the level limit";
  while (static_cast<int>(undone.size()) < options.max_levels) {
    Compacted c = Compact(faces, n);
    auto rings = VertexRings::Build(
        static_cast<uint32_t>(c.local_to_global.size()), c.faces);
    if (!rings.ok()) {
      stop_reason = "the coarser mesh would not be manifold: " +
                    rings.status().message();
      break;
    }
    auto level = LevelUndoer(*rings, c.faces).Run();
    if (!level.ok()) {
      stop_reason = level.status().message();
      break;
    }
    // Back to global ids.
    UndoneLevel global;
    for (Face f : level->coarse_faces) {
      for (uint32_t& v : f) v = c.local_to_global[v];
      global.coarse_faces.push_back(f);
    }
    global.edge_to_odd.reserve(level->edge_to_odd.size());
    for (const auto& [key, odd] : level->edge_to_odd) {
      const uint32_t a = c.local_to_global[key >> 32];
      const uint32_t b = c.local_to_global[key & 0xffffffffu];
      global.edge_to_odd.emplace(EdgeKey(a, b), c.local_to_global[odd]);
    }
    // The coarse mesh must itself be a valid base: manifold and oriented.
    Compacted coarse = Compact(global.coarse_faces, n);
    auto coarse_rings = VertexRings::Build(
        static_cast<uint32_t>(coarse.local_to_global.size()), coarse.faces);
    if (!coarse_rings.ok()) {
      stop_reason = "undoing one more level gives a non-manifold mesh: " +
                    coarse_rings.status().message();
      break;
    }
    faces = global.coarse_faces;
    undone.push_back(std::move(global));
  }
  if (undone.empty()) {
    return Status(StatusCode::kNotSemiRegular,
                  "no level of 1-to-4 subdivision found: " + stop_reason);
  }

  // Canonical renumbering from the recovered base mesh.
  Compacted base = Compact(faces, n);
  const int levels = static_cast<int>(undone.size());
  MW_ASSIGN_OR_RETURN(
      auto hierarchy,
      SemiRegularHierarchy::Build(
          static_cast<uint32_t>(base.local_to_global.size()), base.faces,
          levels));
  DetectedSemiRegular out;
  out.stop_reason = stop_reason;
  out.original_index = base.local_to_global;
  out.original_index.resize(hierarchy->vertex_count(levels));
  for (int j = 0; j < levels; ++j) {
    const UndoneLevel& u = undone[levels - 1 - j];
    const uint32_t vj = hierarchy->vertex_count(j);
    const auto& edges = hierarchy->edges(j);
    for (size_t k = 0; k < edges.size(); ++k) {
      auto it = u.edge_to_odd.find(EdgeKey(out.original_index[edges[k][0]],
                                           out.original_index[edges[k][1]]));
      if (it == u.edge_to_odd.end()) {
        return Status(StatusCode::kInternal,
                      "recovered hierarchy lost an edge at level " +
                          std::to_string(j));
      }
      out.original_index[vj + k] = it->second;
    }
  }
  if (out.original_index.size() != n) {
    return Status(StatusCode::kInternal, "renumbering lost vertices");
  }
  out.mesh.hierarchy = hierarchy;
  out.mesh.positions.resize(n);
  for (size_t v = 0; v < n; ++v) {
    out.mesh.positions[v] = mesh.positions[out.original_index[v]];
  }
  return out;
}

}  // namespace meshwave
