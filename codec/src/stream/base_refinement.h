// The base mesh's positions in embedded form (docs/FORMAT.md 3.3). The
// header carries every base coordinate on a grid 2^R times coarser than the
// finest; R packets then send the R low bits of every finest-grid
// coordinate, most significant first, one bit per coordinate each. A
// decoder missing the m lowest bits places a coordinate in the middle of the
// 2^m finest cells it can still be in, so every prefix of the refinement is
// a usable base, and the packet order spends the bytes on the base's low
// bits only when they are worth more than details (a coarse base is what a
// low-rate prefix needs: the fine base was 75-99 % of the bunny's,
// elephant's and fandisk's qp-8 prefixes against Draco).
#ifndef MESHWAVE_STREAM_BASE_REFINEMENT_H_
#define MESHWAVE_STREAM_BASE_REFINEMENT_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// Bytes of one refinement packet: one bit per coordinate, 3 per vertex.
size_t BaseRefinementBytes(uint32_t vertex_count);

// The packet of bitplane `plane` (R-1 down to 0) of the finest-grid
// residuals (each coordinate in [0, 2^R)): bit 3 v + a of the payload (byte
// k / 8, bit k % 8 from the least significant) is bit `plane` of vertex v's
// coordinate a.
std::string EncodeBaseRefinementPlane(std::span<const IntVec3> residual, int plane);

// Adds the bits of packet `plane` to `known` (each coordinate's bits above
// `plane` already there). Checks the length only: every bit pattern is a
// valid refinement.
Status DecodeBaseRefinementPlane(std::string_view payload, int plane,
                                 std::vector<IntVec3>& known);

// The position of a base vertex with coarse grid coordinates `coarse`
// whose residual is known from bit `missing` up (`known`, lower bits 0):
// origin + step * (2^R coarse + known + (2^missing - 1) / 2).
Vec3 RefinedBasePosition(const StreamHeader::BaseMesh& base, const IntVec3& coarse,
                         const IntVec3& known, int missing);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_REFINEMENT_H_
