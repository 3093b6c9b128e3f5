// The base mesh M^0's decoder (docs/FORMAT.md section 3): connectivity and
// integer-grid positions from the header, then the base refinement packets.
#ifndef MESHWAVE_STREAM_BASE_MESH_DECODER_H_
#define MESHWAVE_STREAM_BASE_MESH_DECODER_H_

#include <cstdint>
#include <string_view>
#include <vector>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

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

#endif  // MESHWAVE_STREAM_BASE_MESH_DECODER_H_
