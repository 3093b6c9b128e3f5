// The encoder of the base refinement packets (stream/base_refinement.h).
#ifndef MESHWAVE_STREAM_BASE_REFINEMENT_ENCODER_H_
#define MESHWAVE_STREAM_BASE_REFINEMENT_ENCODER_H_

#include <span>
#include <string>

#include "bitplane/coefficient_octree.h"  // IntVec3

namespace meshwave {

// The packet of bitplane `plane` (R-1 down to 0) of the finest-grid
// residuals (each coordinate in [0, 2^R)): bit 3 v + a of the payload (byte
// k / 8, bit k % 8 from the least significant) is bit `plane` of vertex v's
// coordinate a.
std::string EncodeBaseRefinementPlane(std::span<const IntVec3> residual, int plane);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_REFINEMENT_ENCODER_H_
