#include "stream/base_connectivity.h"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>

#include "core/edge_index_table.h"
#include "core/edge_key.h"
#include "entropy/adaptive_golomb.h"

namespace meshwave {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
// Faces an untrusted count may reserve edge-table room for before they decode.
constexpr uint64_t kUntrustedFacesAhead = uint64_t{1} << 16;

struct ConnectivityContexts {
  BinaryContext is_new_first;  // corners of a component's first face
  BinaryContext is_new_third;  // the third vertex of a face entered by a gate
  BinaryContext flipped;       // face oriented against the one it is entered from
  BinaryContext on_border;
  GolombContexts border_index;
  GolombContexts back;         // next_new - 1 - v for any older vertex
  BinaryContext enters[3];     // by edge slot of the face just coded
};

// An edge of a coded face through which a face not yet coded is entered,
// directed as in the coded face.
struct Gate {
  uint32_t a, b;
};

// What both sides know: how many coded faces use each edge, and for every
// vertex its neighbours across "open" edges (used by one coded face): the
// border of the region coded so far.
class CodedRegion {
 public:
  // For a region of about `faces` faces (a closed mesh's edges: 3/2 per face).
  CodedRegion(uint32_t vertex_count, size_t faces)
      : uses_(faces * 3 / 2), open_(vertex_count) {}

  uint32_t Uses(uint32_t a, uint32_t b) const {
    const uint32_t* n = uses_.Find(a, b);
    return n == nullptr ? 0 : *n;
  }

  // False when an edge would be in a third face (not a manifold mesh).
  bool Add(const Face& f) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t a = f[c], b = f[(c + 1) % 3];
      uint32_t& n = uses_.Emplace(a, b, 0).first;
      if (n >= 2) return false;
      if (++n == 1) {
        open_[a].push_back(b);
        open_[b].push_back(a);
      } else {
        Erase(open_[a], b);
        Erase(open_[b], a);
      }
    }
    return true;
  }

  // Vertices across open edges from a, then from b, latest first.
  void BorderCandidates(uint32_t a, uint32_t b, std::vector<uint32_t>& out) const {
    out.clear();
    for (uint32_t v : {a, b}) {
      for (auto it = open_[v].rbegin(); it != open_[v].rend(); ++it) {
        if (*it != a && *it != b && std::find(out.begin(), out.end(), *it) == out.end()) {
          out.push_back(*it);
        }
      }
    }
  }

 private:
  static void Erase(std::vector<uint32_t>& list, uint32_t v) {
    auto it = std::find(list.begin(), list.end(), v);
    if (it != list.end()) list.erase(it);
  }

  EdgeIndexTable uses_;  // faces coded per edge
  std::vector<std::vector<uint32_t>> open_;
};

bool Distinct(const Face& f) { return f[0] != f[1] && f[1] != f[2] && f[0] != f[2]; }

// Which edges of a face just coded (from slot `first`) still need their
// "enters" bit: those no other coded face uses.
std::array<bool, 3> EdgesToAsk(const CodedRegion& region, const Face& f, int first) {
  std::array<bool, 3> ask{false, false, false};
  for (int c = first; c < 3; ++c) ask[c] = region.Uses(f[c], f[(c + 1) % 3]) == 0;
  return ask;
}

}  // namespace

Result<BaseMeshOrder> TraverseBaseMesh(uint32_t vertex_count, const std::vector<Face>& faces,
                                       ArithmeticEncoder* enc) {
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> by_edge;
  by_edge.reserve(faces.size() * 2);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (!Distinct(faces[f]) || *std::max_element(faces[f].begin(), faces[f].end()) >= vertex_count) {
      return InvalidArgument("base face " + std::to_string(f) + " is degenerate or out of range");
    }
    for (int c = 0; c < 3; ++c) {
      auto [it, fresh] = by_edge.try_emplace(EdgeKey(faces[f][c], faces[f][(c + 1) % 3]),
                                             std::array<uint32_t, 2>{kNone, kNone});
      if (it->second[1] != kNone) {
        return InvalidArgument("base mesh edge in more than two faces (face " +
                               std::to_string(f) + ")");
      }
      (it->second[0] == kNone ? it->second[0] : it->second[1]) = f;
    }
  }
  const auto across = [&](uint32_t f, uint32_t a, uint32_t b) {
    const auto& pair = by_edge.at(EdgeKey(a, b));
    return pair[0] == f ? pair[1] : pair[0];
  };

  BaseMeshOrder out;
  out.new_of_old.assign(vertex_count, kNone);
  out.faces.reserve(faces.size());
  std::vector<uint32_t> old_of_new;
  old_of_new.reserve(vertex_count);
  std::vector<char> taken(faces.size(), 0);  // coded or waiting behind a gate
  CodedRegion region(vertex_count, faces.size());
  ConnectivityContexts ctx;
  std::vector<std::pair<Gate, uint32_t>> stack;  // gate and the face behind it
  std::vector<uint32_t> candidates;

  const auto number = [&](uint32_t old) {
    if (out.new_of_old[old] == kNone) {
      out.new_of_old[old] = static_cast<uint32_t>(old_of_new.size());
      old_of_new.push_back(old);
    }
    return out.new_of_old[old];
  };
  const auto code_older = [&](uint32_t v) {
    if (enc) EncodeGolomb(*enc, ctx.back, static_cast<uint32_t>(old_of_new.size()) - 1 - v);
  };
  // Records a face (old ids `of`, already rotated) and opens its gates.
  const auto finish = [&](uint32_t f, const Face& of, int first) {
    Face nf;
    for (int c = 0; c < 3; ++c) nf[c] = out.new_of_old[of[c]];
    const std::array<bool, 3> ask = EdgesToAsk(region, nf, first);
    region.Add(nf);  // cannot fail: edges were checked above
    out.faces.push_back(nf);
    std::array<std::pair<Gate, uint32_t>, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (!ask[c]) continue;
      const uint32_t g = across(f, of[c], of[(c + 1) % 3]);
      const bool enters = g != kNone && !taken[g];
      if (enc) enc->Encode(enters, ctx.enters[c]);
      if (enters) {
        taken[g] = 1;
        opened[n++] = {Gate{nf[c], nf[(c + 1) % 3]}, g};
      }
    }
    // Depth first, lowest slot first: neighbours stay close in the order.
    while (n > 0) stack.push_back(opened[--n]);
  };

  for (uint32_t start = 0; start < faces.size(); ++start) {
    if (taken[start]) continue;
    taken[start] = 1;
    for (uint32_t old : faces[start]) {
      const bool fresh = out.new_of_old[old] == kNone;
      if (enc) enc->Encode(fresh, ctx.is_new_first);
      if (!fresh) code_older(out.new_of_old[old]);
      number(old);
    }
    finish(start, faces[start], 0);
    while (!stack.empty()) {
      const auto [gate, g] = stack.back();
      stack.pop_back();
      const uint32_t a = old_of_new[gate.a], b = old_of_new[gate.b];
      const Face& f = faces[g];
      Face of{};
      bool flipped = false;
      for (int c = 0; c < 3; ++c) {
        const uint32_t u = f[c], w = f[(c + 1) % 3], x = f[(c + 2) % 3];
        if (u == b && w == a) of = {b, a, x};
        if (u == a && w == b) {
          of = {a, b, x};
          flipped = true;
        }
      }
      if (enc) enc->Encode(flipped, ctx.flipped);
      const bool fresh = out.new_of_old[of[2]] == kNone;
      if (enc) enc->Encode(fresh, ctx.is_new_third);
      if (!fresh) {
        const uint32_t v = out.new_of_old[of[2]];
        region.BorderCandidates(gate.a, gate.b, candidates);
        const auto it = std::find(candidates.begin(), candidates.end(), v);
        if (enc) enc->Encode(it != candidates.end(), ctx.on_border);
        if (it != candidates.end()) {
          if (enc) {
            EncodeGolomb(*enc, ctx.border_index, static_cast<uint32_t>(it - candidates.begin()));
          }
        } else {
          code_older(v);
        }
      }
      number(of[2]);
      finish(g, of, 1);
    }
  }
  out.used_vertices = static_cast<uint32_t>(old_of_new.size());
  for (uint32_t& id : out.new_of_old) {
    if (id == kNone) id = static_cast<uint32_t>(old_of_new.size()), old_of_new.push_back(0);
  }
  return out;
}

Result<std::vector<Face>> DecodeBaseConnectivity(ArithmeticDecoder& dec, uint32_t vertex_count,
                                                 uint64_t face_count) {
  std::vector<Face> faces;
  faces.reserve(face_count);
  // The count is the stream's word: the edge table has room for at most
  // kUntrustedFacesAhead faces ahead and grows with the faces that decode.
  CodedRegion region(vertex_count, std::min<uint64_t>(face_count, kUntrustedFacesAhead));
  ConnectivityContexts ctx;
  std::vector<Gate> stack;
  std::vector<uint32_t> candidates;
  uint32_t next_new = 0;
  const auto fail = [&](const std::string& what) {
    return ParseError("base mesh: face " + std::to_string(faces.size()) + " " + what);
  };
  // False when the bytes name a vertex that cannot exist yet.
  const auto read_vertex = [&](BinaryContext& is_new, uint32_t& v) {
    if (dec.Decode(is_new)) {
      if (next_new >= vertex_count) return false;
      v = next_new++;
      return true;
    }
    const uint32_t back = DecodeGolomb(dec, ctx.back);
    if (back >= next_new) return false;
    v = next_new - 1 - back;
    return true;
  };
  while (faces.size() < face_count) {
    if ((faces.size() & 1023) == 0 && dec.overrun()) return fail("is missing: bytes end");
    Face f{};
    int first = 0;
    if (stack.empty()) {
      for (int c = 0; c < 3; ++c) {
        if (!read_vertex(ctx.is_new_first, f[c])) return fail("names a vertex not seen yet");
      }
    } else {
      const Gate gate = stack.back();
      stack.pop_back();
      const bool flipped = dec.Decode(ctx.flipped);
      uint32_t x = 0;
      if (dec.Decode(ctx.is_new_third)) {
        if (next_new >= vertex_count) return fail("introduces more vertices than announced");
        x = next_new++;
      } else if (region.BorderCandidates(gate.a, gate.b, candidates), dec.Decode(ctx.on_border)) {
        const uint32_t i = DecodeGolomb(dec, ctx.border_index);
        if (i >= candidates.size()) return fail("names a border vertex that does not exist");
        x = candidates[i];
      } else {
        const uint32_t back = DecodeGolomb(dec, ctx.back);
        if (back >= next_new) return fail("names a vertex not seen yet");
        x = next_new - 1 - back;
      }
      f = flipped ? Face{gate.a, gate.b, x} : Face{gate.b, gate.a, x};
      first = 1;
    }
    if (!Distinct(f)) return fail("repeats a vertex");
    const std::array<bool, 3> ask = EdgesToAsk(region, f, first);
    if (!region.Add(f)) return fail("puts an edge in a third face");
    faces.push_back(f);
    std::array<Gate, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (ask[c] && dec.Decode(ctx.enters[c])) opened[n++] = Gate{f[c], f[(c + 1) % 3]};
    }
    while (n > 0) stack.push_back(opened[--n]);
  }
  if (!stack.empty()) return ParseError("base mesh: faces announced behind edges never come");
  if (next_new != vertex_count) {
    return ParseError("base mesh: faces use " + std::to_string(next_new) + " of " +
                      std::to_string(vertex_count) + " vertices");
  }
  return faces;
}

}  // namespace meshwave
