// The encoder of the base mesh's connectivity (connectivity/gate_traversal.h):
// the traversal that orders the base mesh for transmission, writing its
// code as it goes.
#ifndef MESHWAVE_STREAM_BASE_CONNECTIVITY_ENCODER_H_
#define MESHWAVE_STREAM_BASE_CONNECTIVITY_ENCODER_H_

#include <cstdint>
#include <vector>

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

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_CONNECTIVITY_ENCODER_H_
