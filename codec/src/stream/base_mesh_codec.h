// The base mesh M^0: connectivity and integer-grid positions, coded with the
// arithmetic coder (docs/FORMAT.md section 3).
#ifndef MESHWAVE_STREAM_BASE_MESH_CODEC_H_
#define MESHWAVE_STREAM_BASE_MESH_CODEC_H_

#include <string_view>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "stream/base_connectivity.h"
#include "stream/base_refinement.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// The order the base mesh travels in (stream/base_connectivity.h): faces
// in a depth-first traversal over shared edges, each rotated to start at
// the edge it is entered by; vertices numbered by first appearance. Errors
// for faces that are degenerate or share an edge three times.
Result<BaseMeshOrder> ChooseTransmissionOrder(uint32_t vertex_count,
                                              const std::vector<Face>& faces);

struct DecodedBase {
  // Where the refinement received so far places the vertices
  // (RefinedBasePosition).
  std::vector<Vec3> positions;
  // The header's coarse grid: what the octrees and SAWT regions are built
  // on, the same for every truncation of the stream.
  std::vector<IntVec3> grid;
  std::vector<Face> faces;
  std::vector<IntVec3> refinement;  // the residuals' bits received so far
  int missing_planes = 0;           // R, until refinement packets come
};

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

// Safe on untrusted input: counts are capped and checked as decoding goes.
// The result holds no refinement (missing_planes = R).
Result<DecodedBase> DecodeBaseMesh(const StreamHeader::BaseMesh& base,
                                   uint32_t max_vertices);

// Adds refinement packet `plane`, which must be the next one
// (missing_planes - 1), and moves the vertices.
Status RefineBase(const StreamHeader::BaseMesh& header, int plane, std::string_view payload,
                  DecodedBase& base);
// Back to no refinement at all.
void ForgetBaseRefinement(const StreamHeader::BaseMesh& header, DecodedBase& base);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_MESH_CODEC_H_
