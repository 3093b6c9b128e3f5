// What the original layer's connectivity encoder and decoder
// (original_connectivity.h) must agree on: the contexts, the prediction of
// each new vertex's original id, and the form of the faces left to the
// fallback list.
//
// The code, one arithmetic-coded payload:
//   per component of the traversal: a 1 ("another component"), its first
//     face's three corners, then the base mesh's depth-first traversal
//     (connectivity/gate_traversal.h) over gates: per face entered, "flipped",
//     "new third vertex", else "on the border" + index (two binary
//     decisions, then a Golomb code) or "older" + how far back in the
//     order; per open edge of a coded face, "enters";
//   a 0 (no more components);
//   how many fallback faces follow;
//   the fallback faces (those the traversal cannot take: a repeated corner,
//     an edge that would be in a third face), each rotated to start at its
//     smallest id and sorted: that id minus the previous face's, then the
//     two other corners minus it;
//   how many vertices are in no face (they come last in the order,
//     ascending).
// Each vertex the traversal introduces codes its original id: its place in
// a short list of likely ids (IdCandidates), else its distance from the
// last id introduced plus one.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "entropy/adaptive_golomb.h"
#include "meshwave/mesh.h"
#include "original/original_traversal.h"
#include "connectivity/gate_traversal.h"

namespace meshwave::original {

struct ConnectivityContexts {
  connectivity::ConnectivityContexts traversal;  // the base mesh's symbols
  BinaryContext another_component;
  // The border candidate's index: 0?, by how many candidates (2, 3, more);
  // then 1?; then the rest as a Golomb code of index - 2.
  BinaryContext border_first[3];
  BinaryContext border_second;
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

// The ids a new vertex likely has, best first. Files list vertices in
// runs (scan lines, strips, the order an exporter met them) or on grids,
// and a traversal walks several runs at once: so the candidates are the
// successors of ids introduced lately, the last id plus one, the gate's
// ids plus or minus one, and the parallelogram a + b - c in ids (exact on
// a row-major grid). Each kind of guess is ranked by how often it was
// right so far, so the list adapts to the file's habits.
class IdCandidates {
 public:
  static constexpr size_t kRecent = 8;  // successors of recent ids kept
  static constexpr size_t kSteps = 4;   // recent id steps from a gate vertex
  static constexpr int kKinds = 7 + static_cast<int>(kRecent + 2 * kSteps);

  IdCandidates() {
    for (int k = 0; k < kKinds; ++k) rank_[k] = k;
  }

  // The distinct candidates for a vertex whose position prediction is p,
  // each an id below vertex_count not yet in the order (position[id] ==
  // kNoVertex), best first.
  const std::vector<uint32_t>& For(const Prediction& p, uint32_t vertex_count,
                                   const std::vector<uint32_t>& position) {
    std::array<int64_t, kKinds> guess;
    Guesses(p, guess);
    ids_.clear();
    for (int k : rank_) {
      const int64_t id = guess[k];
      if (id < 0 || id >= vertex_count || position[static_cast<uint32_t>(id)] != kNoVertex) continue;
      const uint32_t v = static_cast<uint32_t>(id);
      if (std::find(ids_.begin(), ids_.end(), v) == ids_.end()) ids_.push_back(v);
    }
    return ids_;
  }

  // `id` was introduced with prediction p (after For(p, ...)).
  void Introduce(uint32_t id, const Prediction& p, uint32_t vertex_count,
                 const std::vector<uint32_t>& position) {
    std::array<int64_t, kKinds> guess;
    Guesses(p, guess);
    bool moved = false;
    for (int k = 0; k < kKinds; ++k) {
      if (guess[k] == int64_t{id}) ++hits_[k], moved = true;
    }
    if (moved) {
      std::stable_sort(rank_.begin(), rank_.end(), [&](int x, int y) { return hits_[x] > hits_[y]; });
    }
    last_ = id;
    if (p.a != kNoVertex) {
      const int64_t step = int64_t{id} - p.a;
      const auto at = std::find(steps_.begin(), steps_.end(), step);
      if (at != steps_.end()) steps_.erase(at);
      if (steps_.size() == kSteps) steps_.erase(steps_.begin());
      steps_.push_back(step);
    }
    const auto it = std::find(recent_.begin(), recent_.end(), id);
    if (it != recent_.end()) recent_.erase(it);
    const uint32_t next = id + 1;
    if (next < vertex_count && position[next] == kNoVertex &&
        std::find(recent_.begin(), recent_.end(), next) == recent_.end()) {
      if (recent_.size() == kRecent) recent_.erase(recent_.begin());
      recent_.push_back(next);
    }
  }

  // The last id introduced plus one: where an id not in the list is
  // counted from.
  int64_t Next() const { return last_ + 1; }

 private:
  void Guesses(const Prediction& p, std::array<int64_t, kKinds>& guess) const {
    constexpr int64_t kNone = -1;
    const auto id = [](uint32_t v) { return v == kNoVertex ? kNone : int64_t{v}; };
    const int64_t a = id(p.a), b = id(p.b), c = id(p.c);
    guess[0] = c != kNone ? a + b - c : kNone;
    guess[1] = last_ + 1;
    guess[2] = a != kNone ? a + 1 : kNone;
    guess[3] = a != kNone ? a - 1 : kNone;
    guess[4] = b != kNone ? b + 1 : kNone;
    guess[5] = b != kNone ? b - 1 : kNone;
    guess[6] = c != kNone ? c + 1 : kNone;
    for (size_t i = 0; i < kRecent; ++i) {
      guess[7 + i] = i < recent_.size() ? int64_t{recent_[recent_.size() - 1 - i]} : kNone;
    }
    for (size_t i = 0; i < kSteps; ++i) {
      const bool known = i < steps_.size();
      const int64_t step = known ? steps_[steps_.size() - 1 - i] : 0;
      guess[7 + kRecent + 2 * i] = known && a != kNone ? a + step : kNone;
      guess[8 + kRecent + 2 * i] = known && b != kNone ? b + step : kNone;
    }
  }

  std::array<int, kKinds> rank_;
  std::array<uint32_t, kKinds> hits_{};
  std::vector<uint32_t> recent_;  // most recent last
  std::vector<int64_t> steps_;    // id - a of recent introductions, most recent last
  std::vector<uint32_t> ids_;
  int64_t last_ = -1;
};

inline BinaryContext& FirstBorderContext(ConnectivityContexts& ctx, size_t candidates) {
  return ctx.border_first[std::min<size_t>(candidates, 4) - 2 + (candidates < 2 ? 2 : 0)];
}

// A fallback face rotated to start at its smallest corner (cyclic order
// kept: a rotation, never a reflection).
inline Face RotateToSmallest(const Face& f) {
  const int m = f[1] < f[0] ? (f[2] < f[1] ? 2 : 1) : (f[2] < f[0] ? 2 : 0);
  return Face{f[m], f[(m + 1) % 3], f[(m + 2) % 3]};
}

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_CODE_H_
