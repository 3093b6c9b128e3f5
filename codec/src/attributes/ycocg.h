// The colour space a colour channel is coded in: YCoCg in floating point
// (Malvar and Sullivan, "YCoCg-R: A Color Space with RGB Reversibility and
// Low Dynamic Range", JVT-I014, 2003). Its luma takes most of a natural
// colour signal's energy and the two chroma planes little, so the bitplane
// coder spends its bits where they show. Float, not the integer -R form:
// the channel is lifted and quantised in doubles like the geometry, and
// reversibility is lost at quantisation anyway. Shared by the encoder and
// the decoder, which must agree on it exactly.
#ifndef MESHWAVE_ATTRIBUTES_YCOCG_H_
#define MESHWAVE_ATTRIBUTES_YCOCG_H_

#include "meshwave/mesh.h"

namespace meshwave {

// Linear RGB to (Y, Co, Cg): Y = R/4 + G/2 + B/4, Co = R/2 - B/2,
// Cg = -R/4 + G/2 - B/4. RGB in [0, 1] gives Y in [0, 1] and Co, Cg in
// [-1/2, 1/2].
inline Vec3 RgbToYCoCg(const Vec3& rgb) {
  return {0.25 * rgb[0] + 0.5 * rgb[1] + 0.25 * rgb[2], 0.5 * (rgb[0] - rgb[2]),
          -0.25 * rgb[0] + 0.5 * rgb[1] - 0.25 * rgb[2]};
}

// The exact inverse of RgbToYCoCg (no clamping: a quantised colour may
// leave [0, 1]; writers clamp).
inline Vec3 YCoCgToRgb(const Vec3& ycocg) {
  const double t = ycocg[0] - ycocg[2];
  return {t + ycocg[1], ycocg[0] + ycocg[2], t - ycocg[1]};
}

}  // namespace meshwave

#endif  // MESHWAVE_ATTRIBUTES_YCOCG_H_
