#include "stream/base_mesh_codec.h"

#include <cmath>
#include <string>
#include <unordered_map>

#include "entropy/adaptive_golomb.h"

namespace meshwave {
namespace {

uint64_t EdgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return (uint64_t{a} << 32) | b;
}

// The connectivity code: each corner is a new vertex (the next index), a
// vertex in a small move-to-front cache of recently used ones (coded by its
// cache slot), or an older one (coded by how far back it is).
class CornerCoder {
 public:
  static constexpr size_t kCacheSize = 16;

  void Encode(ArithmeticEncoder& enc, int corner, uint32_t v, uint32_t next_new) {
    enc.Encode(v == next_new, is_new_[corner]);
    if (v == next_new) {
      Touch(v, cache_.size());
      return;
    }
    const size_t slot = Find(v);
    enc.Encode(slot < cache_.size(), in_cache_);
    if (slot < cache_.size()) {
      EncodeGolomb(enc, slot_, static_cast<uint32_t>(slot));
    } else {
      EncodeGolomb(enc, back_, next_new - 1 - v);
    }
    Touch(v, slot);
  }

  // Returns false when the bytes name a vertex that cannot exist.
  bool Decode(ArithmeticDecoder& dec, int corner, uint32_t& next_new, uint32_t& v) {
    if (dec.Decode(is_new_[corner])) {
      v = next_new++;
      Touch(v, cache_.size());
      return true;
    }
    if (dec.Decode(in_cache_)) {
      const uint32_t slot = DecodeGolomb(dec, slot_);
      if (slot >= cache_.size()) return false;
      v = cache_[slot];
      Touch(v, slot);
      return true;
    }
    const uint32_t back = DecodeGolomb(dec, back_);
    if (back >= next_new) return false;
    v = next_new - 1 - back;
    Touch(v, Find(v));
    return true;
  }

 private:
  size_t Find(uint32_t v) const {
    for (size_t i = 0; i < cache_.size(); ++i) {
      if (cache_[i] == v) return i;
    }
    return cache_.size();
  }
  // Moves v to the front (slot == size: not in the cache yet).
  void Touch(uint32_t v, size_t slot) {
    if (slot == cache_.size()) {
      if (cache_.size() < kCacheSize) cache_.push_back(v);
      slot = cache_.size() - 1;
    }
    for (size_t i = slot; i > 0; --i) cache_[i] = cache_[i - 1];
    cache_[0] = v;
  }

  std::vector<uint32_t> cache_;
  BinaryContext is_new_[3];
  BinaryContext in_cache_;
  GolombContexts slot_;
  GolombContexts back_;
};

// Contexts of the position code.
struct PositionContexts {
  SignedGolombContexts residual[3];
};

// The prediction of vertex v's grid position from vertices < v: across an
// edge of the face where v first appears (parallelogram), else the mean of
// that face's known corners, else the previous vertex.
class PositionPredictor {
 public:
  PositionPredictor(const std::vector<Face>& faces, uint32_t vertex_count)
      : faces_(faces), first_face_(vertex_count, kNoFace) {
    for (uint32_t f = 0; f < faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = faces[f][c];
        if (first_face_[v] == kNoFace) first_face_[v] = f;
        auto [it, fresh] = edge_faces_.try_emplace(
            EdgeKey(v, faces[f][(c + 1) % 3]), std::array<uint32_t, 2>{kNoFace, kNoFace});
        (it->second[0] == kNoFace ? it->second[0] : it->second[1]) = f;
      }
    }
  }

  IntVec3 Predict(uint32_t v, const std::vector<IntVec3>& grid) const {
    const uint32_t f = first_face_[v];
    uint32_t known[2];
    int n = 0;
    if (f != kNoFace) {
      for (uint32_t u : faces_[f]) {
        if (u < v && n < 2) known[n++] = u;
      }
    }
    if (n == 2) {
      auto it = edge_faces_.find(EdgeKey(known[0], known[1]));
      if (it != edge_faces_.end()) {
        for (uint32_t g : it->second) {
          if (g == kNoFace || g == f) continue;
          for (uint32_t c : faces_[g]) {
            if (c != known[0] && c != known[1] && c < v) {
              IntVec3 p;
              for (int a = 0; a < 3; ++a) {
                p[a] = grid[known[0]][a] + grid[known[1]][a] - grid[c][a];
              }
              return p;
            }
          }
        }
      }
      IntVec3 p;
      for (int a = 0; a < 3; ++a) p[a] = (grid[known[0]][a] + grid[known[1]][a]) >> 1;
      return p;
    }
    if (n == 1) return grid[known[0]];
    if (v > 0) return grid[v - 1];
    return {0, 0, 0};
  }

 private:
  static constexpr uint32_t kNoFace = 0xffffffffu;
  const std::vector<Face>& faces_;
  std::vector<uint32_t> first_face_;
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> edge_faces_;
};

}  // namespace

BaseMeshOrder ChooseTransmissionOrder(uint32_t vertex_count,
                                      const std::vector<Face>& faces) {
  // Faces adjacent through an edge.
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> by_edge;
  by_edge.reserve(faces.size() * 2);
  constexpr uint32_t kNone = 0xffffffffu;
  for (uint32_t f = 0; f < faces.size(); ++f) {
    for (int c = 0; c < 3; ++c) {
      auto [it, fresh] = by_edge.try_emplace(EdgeKey(faces[f][c], faces[f][(c + 1) % 3]),
                                             std::array<uint32_t, 2>{kNone, kNone});
      (it->second[0] == kNone ? it->second[0] : it->second[1]) = f;
    }
  }
  BaseMeshOrder order;
  order.new_of_old.assign(vertex_count, kNone);
  std::vector<char> queued(faces.size(), 0);
  uint32_t next = 0;
  for (uint32_t start = 0; start < faces.size(); ++start) {
    if (queued[start]) continue;
    // Depth first, so that most faces share an edge with the face coded
    // just before them and their corners are recent (cheap in the cache).
    std::vector<uint32_t> stack{start};
    queued[start] = 1;
    while (!stack.empty()) {
      const uint32_t f = stack.back();
      stack.pop_back();
      Face renamed;
      for (int c = 0; c < 3; ++c) {
        uint32_t& id = order.new_of_old[faces[f][c]];
        if (id == kNone) id = next++;
        renamed[c] = id;
      }
      order.faces.push_back(renamed);
      for (int c = 2; c >= 0; --c) {
        for (uint32_t g : by_edge[EdgeKey(faces[f][c], faces[f][(c + 1) % 3])]) {
          if (g != kNone && !queued[g]) {
            queued[g] = 1;
            stack.push_back(g);
          }
        }
      }
    }
  }
  for (uint32_t& id : order.new_of_old) {
    if (id == kNone) id = next++;  // unused vertices (not in a valid base)
  }
  return order;
}

Result<proto::BaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces,
                                       double step) {
  if (positions.empty() || faces.empty()) return InvalidArgument("empty base mesh");
  if (!(step > 0) || !std::isfinite(step)) {
    return InvalidArgument("base quantisation step must be positive");
  }
  Vec3 origin = positions[0];
  for (const Vec3& p : positions) origin = origin.cwiseMin(p);
  std::vector<IntVec3> grid(positions.size());
  for (size_t v = 0; v < positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const double x = std::round((positions[v][a] - origin[a]) / step);
      if (!(x >= 0) || x >= 2147483647.0) {
        return InvalidArgument("base mesh does not fit a 31-bit grid at this precision");
      }
      grid[v][a] = static_cast<int64_t>(x);
    }
  }
  ArithmeticEncoder enc;
  CornerCoder corners;
  uint32_t next_new = 0;
  for (const Face& f : faces) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = f[c];
      if (v > next_new) {
        return Status(StatusCode::kInternal, "base faces are not in transmission order");
      }
      corners.Encode(enc, c, v, next_new);
      if (v == next_new) ++next_new;
    }
  }
  if (next_new != positions.size()) {
    return Status(StatusCode::kInternal, "base faces do not use every vertex");
  }
  const PositionPredictor predictor(faces, next_new);
  PositionContexts pc;
  for (uint32_t v = 0; v < next_new; ++v) {
    const IntVec3 p = predictor.Predict(v, grid);
    for (int a = 0; a < 3; ++a) EncodeSignedGolomb(enc, pc.residual[a], grid[v][a] - p[a]);
  }
  proto::BaseMesh out;
  out.set_vertex_count(static_cast<uint32_t>(positions.size()));
  out.set_face_count(static_cast<uint32_t>(faces.size()));
  for (int a = 0; a < 3; ++a) out.add_origin(origin[a]);
  out.set_step(step);
  out.set_coded(enc.Finish());
  return out;
}

Result<DecodedBase> DecodeBaseMesh(const proto::BaseMesh& base, uint32_t max_vertices) {
  const uint64_t v = base.vertex_count(), f = base.face_count();
  if (v < 3 || f == 0) return ParseError("base mesh: too few vertices or no faces");
  if (v > max_vertices) {
    return ParseError("base mesh: " + std::to_string(v) + " vertices exceed the limit of " +
                      std::to_string(max_vertices));
  }
  // A manifold mesh has F = 2V - 4 + 4g - (boundary terms) faces: this bound
  // leaves room for genus up to V/2 and stops absurd counts.
  if (f > 4 * v + 64) {
    return ParseError("base mesh: " + std::to_string(f) + " faces for " +
                      std::to_string(v) + " vertices");
  }
  if (base.origin_size() != 3 || !(base.step() > 0) || !std::isfinite(base.step())) {
    return ParseError("base mesh: bad origin or step");
  }
  for (double o : base.origin()) {
    if (!std::isfinite(o)) return ParseError("base mesh: origin is not finite");
  }
  ArithmeticDecoder dec(base.coded());
  DecodedBase out;
  CornerCoder corners;
  uint32_t next_new = 0;
  for (uint64_t i = 0; i < f; ++i) {
    Face face;
    for (int c = 0; c < 3; ++c) {
      if (!corners.Decode(dec, c, next_new, face[c])) {
        return ParseError("base mesh: face " + std::to_string(i) +
                          " refers to a vertex not seen yet");
      }
      if (next_new > v) {
        return ParseError("base mesh: face " + std::to_string(i) +
                          " introduces more vertices than the " + std::to_string(v) +
                          " announced");
      }
    }
    out.faces.push_back(face);
    if ((i & 1023) == 0 && dec.overrun()) {
      return ParseError("base mesh: coded bytes end before face " + std::to_string(i));
    }
  }
  if (next_new != v) {
    return ParseError("base mesh: faces use " + std::to_string(next_new) + " of " +
                      std::to_string(v) + " vertices");
  }
  const PositionPredictor predictor(out.faces, next_new);
  PositionContexts pc;
  out.grid.resize(v);
  out.positions.resize(v);
  for (uint32_t i = 0; i < v; ++i) {
    const IntVec3 p = predictor.Predict(i, out.grid);
    for (int a = 0; a < 3; ++a) {
      const int64_t q = p[a] + DecodeSignedGolomb(dec, pc.residual[a]);
      if (q < 0 || q > 0x7fffffff) {
        return ParseError("base mesh: vertex " + std::to_string(i) + " leaves the grid");
      }
      out.grid[i][a] = q;
      out.positions[i][a] = base.origin(a) + base.step() * static_cast<double>(q);
    }
  }
  if (dec.overrun()) return ParseError("base mesh: coded bytes truncated");
  return out;
}

}  // namespace meshwave
