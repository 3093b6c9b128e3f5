#include "stream/base_connectivity_decoder.h"

#include <algorithm>
#include <array>
#include <string>

#include "entropy/adaptive_golomb_decoder.h"
#include "connectivity/gate_traversal.h"

namespace meshwave {

Result<std::vector<Face>> DecodeBaseConnectivity(ArithmeticDecoder& dec, uint32_t vertex_count,
                                                 uint64_t face_count) {
  // Faces an untrusted count may reserve edge-table room for before they decode.
  constexpr uint64_t kUntrustedFacesAhead = uint64_t{1} << 16;
  std::vector<Face> faces;
  faces.reserve(face_count);
  // The count is the stream's word: the edge table has room for at most
  // kUntrustedFacesAhead faces ahead and grows with the faces that decode.
  connectivity::CodedRegion region(vertex_count, std::min<uint64_t>(face_count, kUntrustedFacesAhead));
  connectivity::ConnectivityContexts ctx;
  std::vector<connectivity::Gate> stack;
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
      const connectivity::Gate gate = stack.back();
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
    if (!connectivity::Distinct(f)) return fail("repeats a vertex");
    const std::array<bool, 3> ask = connectivity::EdgesToAsk(region, f, first);
    if (!region.Add(f)) return fail("puts an edge in a third face");
    faces.push_back(f);
    std::array<connectivity::Gate, 3> opened;
    int n = 0;
    for (int c = first; c < 3; ++c) {
      if (ask[c] && dec.Decode(ctx.enters[c])) opened[n++] = connectivity::Gate{f[c], f[(c + 1) % 3]};
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
