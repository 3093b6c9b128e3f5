#include "stream/base_connectivity_encoder.h"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>

#include "core/edge_key.h"
#include "entropy/adaptive_golomb_encoder.h"
#include "connectivity/gate_traversal.h"

namespace meshwave {

Result<BaseMeshOrder> TraverseBaseMesh(uint32_t vertex_count, const std::vector<Face>& faces,
                                       ArithmeticEncoder* enc) {
  constexpr uint32_t kNone = 0xffffffffu;
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> by_edge;
  by_edge.reserve(faces.size() * 2);
  for (uint32_t f = 0; f < faces.size(); ++f) {
    if (!connectivity::Distinct(faces[f]) || *std::max_element(faces[f].begin(), faces[f].end()) >= vertex_count) {
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
  connectivity::CodedRegion region(vertex_count, faces.size());
  connectivity::ConnectivityContexts ctx;
  std::vector<std::pair<connectivity::Gate, uint32_t>> stack;  // gate and the face behind it
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
    const std::array<bool, 3> ask = connectivity::EdgesToAsk(region, nf, first);
    region.Add(nf);  // cannot fail: edges were checked above
    out.faces.push_back(nf);
    std::array<std::pair<connectivity::Gate, uint32_t>, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (!ask[c]) continue;
      const uint32_t g = across(f, of[c], of[(c + 1) % 3]);
      const bool enters = g != kNone && !taken[g];
      if (enc) enc->Encode(enters, ctx.enters[c]);
      if (enters) {
        taken[g] = 1;
        opened[n++] = {connectivity::Gate{nf[c], nf[(c + 1) % 3]}, g};
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

}  // namespace meshwave
