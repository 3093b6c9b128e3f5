// The sRGB transfer function (IEC 61966-2-1), for colours stored encoded
// (PLY and OBJ vertex colours) that MeshAsset keeps linear.
#ifndef MESHWAVE_ASSET_SRGB_H_
#define MESHWAVE_ASSET_SRGB_H_

#include <algorithm>
#include <cmath>

namespace meshwave {

// Encoded value in [0, 1] (clamped) to linear.
inline float SrgbToLinear(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return static_cast<float>(v <= 0.04045 ? v / 12.92
                                         : std::pow((v + 0.055) / 1.055, 2.4));
}

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_SRGB_H_
