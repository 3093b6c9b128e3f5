// The gate traversal of a triangle mesh's connectivity, which the base
// mesh's code (docs/FORMAT.md 3.1) and the original layer's (2.5) share: a depth-first
// traversal over shared edges. Each face after the first of its component
// is entered through a "gate" edge of a face already coded, so only its
// third vertex travels: new (the next index), one of the few vertices on the
// open border of the region coded so far next to the gate (nearly always),
// or any older vertex. One bit per edge tells whether a face lies across it
// and enters through it. About 4 bits per face, against 14 for the corner
// cache this replaced.
//
// What the encoder (base_connectivity_encoder.h) and the decoder
// (base_connectivity_decoder.h) must agree on: the contexts, and the coded
// region whose border both sides track.
#ifndef MESHWAVE_CONNECTIVITY_GATE_TRAVERSAL_H_
#define MESHWAVE_CONNECTIVITY_GATE_TRAVERSAL_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/edge_index_table.h"
#include "entropy/adaptive_golomb.h"
#include "meshwave/mesh.h"

namespace meshwave::connectivity {

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

inline bool Distinct(const Face& f) { return f[0] != f[1] && f[1] != f[2] && f[0] != f[2]; }

// Which edges of a face just coded (from slot `first`) still need their
// "enters" bit: those no other coded face uses.
inline std::array<bool, 3> EdgesToAsk(const CodedRegion& region, const Face& f, int first) {
  std::array<bool, 3> ask{false, false, false};
  for (int c = first; c < 3; ++c) ask[c] = region.Uses(f[c], f[(c + 1) % 3]) == 0;
  return ask;
}

}  // namespace meshwave::connectivity

#endif  // MESHWAVE_CONNECTIVITY_GATE_TRAVERSAL_H_
