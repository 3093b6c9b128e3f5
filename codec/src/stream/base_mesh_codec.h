// The base mesh M^0: connectivity and integer-grid positions, coded with the
// arithmetic coder (docs/FORMAT.md section 3).
#ifndef MESHWAVE_STREAM_BASE_MESH_CODEC_H_
#define MESHWAVE_STREAM_BASE_MESH_CODEC_H_

#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "stream/base_connectivity.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// The order the base mesh travels in (stream/base_connectivity.h): faces
// in a depth-first traversal over shared edges, each rotated to start at
// the edge it is entered by; vertices numbered by first appearance. Errors
// for faces that are degenerate or share an edge three times.
Result<BaseMeshOrder> ChooseTransmissionOrder(uint32_t vertex_count,
                                              const std::vector<Face>& faces);

struct DecodedBase {
  std::vector<Vec3> positions;  // origin + step * grid
  std::vector<IntVec3> grid;
  std::vector<Face> faces;
};

// Quantises `positions` with `step` and codes them and the faces, which must
// be in transmission order (vertices numbered by first appearance).
Result<StreamHeader::BaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces,
                                       double step);

// Safe on untrusted input: counts are capped and checked as decoding goes.
Result<DecodedBase> DecodeBaseMesh(const StreamHeader::BaseMesh& base,
                                   uint32_t max_vertices);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_MESH_CODEC_H_
