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
//
// What the encoder (base_refinement_encoder.h) and the decoder
// (base_refinement_decoder.h) agree on: a packet's size and where a vertex
// lies given the bits known.
#ifndef MESHWAVE_STREAM_BASE_REFINEMENT_H_
#define MESHWAVE_STREAM_BASE_REFINEMENT_H_

#include <cstddef>
#include <cstdint>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "meshwave/mesh.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// Bytes of one refinement packet: one bit per coordinate, 3 per vertex.
size_t BaseRefinementBytes(uint32_t vertex_count);

// The position of a base vertex with coarse grid coordinates `coarse`
// whose residual is known from bit `missing` up (`known`, lower bits 0):
// origin + step * (2^R coarse + known + (2^missing - 1) / 2).
Vec3 RefinedBasePosition(const StreamHeader::BaseMesh& base, const IntVec3& coarse,
                         const IntVec3& known, int missing);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_REFINEMENT_H_
