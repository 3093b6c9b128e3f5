// What the original layer's connectivity encoder and decoder
// (original_connectivity.h) must agree on: the contexts, the prediction of
// each new vertex's original id, and the form of the faces left to the
// fallback list.
//
// The code, one arithmetic-coded payload:
//   per component of the traversal: a 1 ("another component"), its first
//     face's three corners, then the base mesh's depth-first traversal
//     (stream/base_connectivity.h) over gates: per face entered, "flipped",
//     "new third vertex", else "on the border" + index or "older" + how far
//     back in the order; per open edge of a coded face, "enters";
//   a 0 (no more components);
//   how many fallback faces follow;
//   the fallback faces (those the traversal cannot take: a repeated corner,
//     an edge that would be in a third face), each rotated to start at its
//     smallest id and sorted: that id minus the previous face's, then the
//     two other corners minus it;
//   how many vertices are in no face (they come last in the order,
//     ascending).
// Each vertex the traversal introduces codes its original id: its place in
// a short list of likely ids (the successors of ids introduced lately),
// else its distance from the last id introduced plus one.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "entropy/adaptive_golomb.h"
#include "meshwave/mesh.h"
#include "original/original_traversal.h"
#include "stream/base_connectivity.h"

namespace meshwave::original {

struct ConnectivityContexts {
  connectivity::ConnectivityContexts traversal;  // the base mesh's symbols
  BinaryContext another_component;
  BinaryContext id_listed;        // the new id is in the likely-id list
  GolombContexts id_list_index;
  SignedGolombContexts id_delta;  // id - (last id introduced + 1)
  GolombContexts fallback_count;  // fallback faces, then vertices in no face
  GolombContexts fallback_first;  // smallest corner - previous face's
  GolombContexts fallback_other;  // other corners - smallest
};

// A coded face's edge (a, b), directed as in that face, whose third corner
// is c: the face across enters through it and its third vertex, when new,
// is predicted by the parallelogram a + b - c.
struct PendingGate {
  uint32_t a, b, c;
};

// The ids a new vertex likely has: files list vertices in runs (scan lines,
// strips, the order an exporter met them), and a traversal walks several
// runs at once, so each id introduced proposes its successor. Most recent
// first; at most kSize.
class LikelyIds {
 public:
  static constexpr size_t kSize = 8;

  const std::vector<uint32_t>& ids() const { return ids_; }

  // `id` is now in the order; `introduced` says which ids already are.
  void Introduce(uint32_t id, uint32_t vertex_count, const std::vector<uint32_t>& position) {
    const auto it = std::find(ids_.begin(), ids_.end(), id);
    if (it != ids_.end()) ids_.erase(it);
    const uint32_t next = id + 1;
    if (next < vertex_count && position[next] == kNoVertex &&
        std::find(ids_.begin(), ids_.end(), next) == ids_.end()) {
      if (ids_.size() == kSize) ids_.pop_back();
      ids_.insert(ids_.begin(), next);
    }
  }

 private:
  std::vector<uint32_t> ids_;
};

// A fallback face rotated to start at its smallest corner (cyclic order
// kept: a rotation, never a reflection).
inline Face RotateToSmallest(const Face& f) {
  const int m = f[1] < f[0] ? (f[2] < f[1] ? 2 : 1) : (f[2] < f[0] ? 2 : 0);
  return Face{f[m], f[(m + 1) % 3], f[(m + 2) % 3]};
}

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_
