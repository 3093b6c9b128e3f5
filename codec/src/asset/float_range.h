// Whether a double read from a file survives conversion to float (the
// asset's UVs, colours and material factors are floats): finite, and no
// larger than FLT_MAX, which would become infinity.
#ifndef MESHWAVE_ASSET_FLOAT_RANGE_H_
#define MESHWAVE_ASSET_FLOAT_RANGE_H_

#include <cmath>
#include <limits>

namespace meshwave {

inline bool FitsFloat(double v) {
  return std::isfinite(v) && std::fabs(v) <= std::numeric_limits<float>::max();
}

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_FLOAT_RANGE_H_
