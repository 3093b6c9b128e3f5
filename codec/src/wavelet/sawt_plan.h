// The spatially adaptive wavelet transform's side information (SAWT,
// Denis et al. 2010a): the regions of the mesh and, per (level, region), which
// of the six prediction filters f1..f6 predicts the odd vertices there.
#ifndef MESHWAVE_WAVELET_SAWT_PLAN_H_
#define MESHWAVE_WAVELET_SAWT_PLAN_H_

#include <cstdint>
#include <vector>

namespace meshwave {

// The six candidate predictors of SAWT, in the order Satti et al. 2011
// list them; the index
// coded in the stream is the enumerator's value.
enum class SawtFilter : uint8_t {
  kButterfly = 0,      // f1: 1/2 (c1+c2) + 1/8 (c3+c4) - 1/16 wings
  kTenseButterfly,     // f2: 1/2 (c1+c2) + 1/4 (c3+c4) - 1/8 wings
  kLoop,               // f3: 3/8 (c1+c2) + 1/8 (c3+c4)
  kEdge,               // f4: 1/2 (c1+c2)
  kAntiEdge,           // f5: 1/2 (c3+c4)
  kHybrid,             // f6: 1/4 (c1+c2+c3+c4)
};
inline constexpr int kSawtFilterCount = 6;

// Octree regions over the base faces (wavelet/sawt_regions.h).
struct SawtRegions {
  // Region (octree leaf, numbered depth-first) of every base face.
  std::vector<uint32_t> face_region;
  uint32_t count = 0;
  // One flag per octree node whose split the decoder cannot infer, in
  // depth-first order: 1 = split into octants.
  std::vector<uint8_t> split_flags;
};

struct SawtPlan {
  SawtRegions regions;
  // filters[j][r]: the filter of region r at level j (odd vertices of
  // M^{j+1}); regions without an odd vertex at level j keep kButterfly.
  std::vector<std::vector<SawtFilter>> filters;
};

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_SAWT_PLAN_H_
