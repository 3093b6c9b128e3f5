// The base mesh M^0's encoder: its transmission order, then its
// connectivity and integer-grid positions coded with the arithmetic coder
// (docs/FORMAT.md section 3).
#ifndef MESHWAVE_STREAM_BASE_MESH_ENCODER_H_
#define MESHWAVE_STREAM_BASE_MESH_ENCODER_H_

#include <cstdint>
#include <vector>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "stream/base_connectivity_encoder.h"

namespace meshwave {

// The order the base mesh travels in (stream/base_connectivity_encoder.h): faces
// in a depth-first traversal over shared edges, each rotated to start at
// the edge it is entered by; vertices numbered by first appearance. Errors
// for faces that are degenerate or share an edge three times.
Result<BaseMeshOrder> ChooseTransmissionOrder(uint32_t vertex_count,
                                              const std::vector<Face>& faces);

struct EncodedBaseMesh {
  StreamHeader::BaseMesh header;
  // Per vertex, the finest-grid coordinates' R low bits: what the
  // refinement packets carry (base_refinement.h).
  std::vector<IntVec3> residual;
};

// Quantises `positions` with `step` and codes them, on a grid 2^planes times
// coarser, and the faces, which must be in transmission order (vertices
// numbered by first appearance).
Result<EncodedBaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces, double step,
                                       uint32_t refinement_planes = 0);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_MESH_ENCODER_H_
