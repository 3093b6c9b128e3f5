// A distance as the reports print it: absolute, in percent of the bounding
// box diagonal, and as PSNR with the diagonal as peak (`compare`, `remesh`).
#ifndef MESHWAVE_TOOLS_MESHWAVE_SCALED_DISTANCE_H_
#define MESHWAVE_TOOLS_MESHWAVE_SCALED_DISTANCE_H_

#include "meshwave.pb.h"

namespace meshwave::cli {

proto::ScaledDistance Scaled(double distance, double diagonal);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_MESHWAVE_SCALED_DISTANCE_H_
