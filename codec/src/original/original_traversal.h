// What the original layer's two codes share (docs/FORMAT.md 2.5): the
// traversal of the original mesh that the connectivity code makes, and
// the order and predictions the positions code follows. The encoder gets
// it from coding the connectivity, the decoder from decoding it, so both
// sides predict each position from the same vertices.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_TRAVERSAL_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_TRAVERSAL_H_

#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::original {

inline constexpr uint32_t kNoVertex = 0xffffffffu;

// How one vertex's position is predicted from vertices coded before it:
// a, b and c: the parallelogram a + b - c; a and b: their midpoint
// (rounded down on the integer grid); a alone: a; none: the vertex before
// it in the order (the grid's origin for the first).
struct Prediction {
  uint32_t a = kNoVertex;
  uint32_t b = kNoVertex;
  uint32_t c = kNoVertex;
};

struct Traversal {
  // The original faces over the original vertex ids, in the order coded.
  // As a set they equal the input's faces (each face's corners may be
  // rotated, never reflected).
  std::vector<Face> faces;
  // Every vertex id 0 ... V-1 exactly once: the order positions travel in.
  std::vector<uint32_t> order;
  // One per entry of `order`; names only vertices earlier in `order`.
  std::vector<Prediction> predictions;
};

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_TRAVERSAL_H_
