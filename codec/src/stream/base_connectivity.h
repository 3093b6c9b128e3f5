// The base mesh's connectivity code (docs/FORMAT.md 3.1): a depth-first
// traversal over shared edges. Each face after the first of its component
// is entered through a "gate" edge of a face already coded, so only its
// third vertex travels: new (the next index), one of the few vertices on the
// open border of the region coded so far next to the gate (nearly always),
// or any older vertex. One bit per edge tells whether a face lies across it
// and enters through it. About 4 bits per face, against 14 for the corner
// cache this replaced.
#ifndef MESHWAVE_STREAM_BASE_CONNECTIVITY_H_
#define MESHWAVE_STREAM_BASE_CONNECTIVITY_H_

#include <cstdint>
#include <vector>

#include "entropy/arithmetic_decoder.h"
#include "entropy/arithmetic_encoder.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

// The order the base mesh travels in: vertices numbered by first appearance
// in the traversal, faces in traversal order, each rotated so that its gate
// edge comes first.
struct BaseMeshOrder {
  std::vector<uint32_t> new_of_old;  // vertex renumbering
  std::vector<Face> faces;           // in new vertex indices
  uint32_t used_vertices = 0;        // vertices in a face (numbered first)
};

// The traversal of an edge-manifold face set (each edge in at most two
// faces) that uses every vertex. With `enc`, also writes the code. Faces
// already in transmission order come back unchanged.
Result<BaseMeshOrder> TraverseBaseMesh(uint32_t vertex_count,
                                       const std::vector<Face>& faces,
                                       ArithmeticEncoder* enc);

// Reads `face_count` faces over `vertex_count` vertices. Safe on untrusted
// bytes: every index and every edge use is checked.
Result<std::vector<Face>> DecodeBaseConnectivity(ArithmeticDecoder& dec,
                                                 uint32_t vertex_count,
                                                 uint64_t face_count);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_CONNECTIVITY_H_
