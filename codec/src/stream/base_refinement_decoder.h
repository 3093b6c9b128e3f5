// The decoder of the base refinement packets (stream/base_refinement.h).
#ifndef MESHWAVE_STREAM_BASE_REFINEMENT_DECODER_H_
#define MESHWAVE_STREAM_BASE_REFINEMENT_DECODER_H_

#include <string_view>
#include <vector>

#include "bitplane/coefficient_octree.h"  // IntVec3
#include "meshwave/status.h"

namespace meshwave {

// Adds the bits of packet `plane` to `known` (each coordinate's bits above
// `plane` already there). Checks the length only: every bit pattern is a
// valid refinement.
Status DecodeBaseRefinementPlane(std::string_view payload, int plane,
                                 std::vector<IntVec3>& known);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_REFINEMENT_DECODER_H_
