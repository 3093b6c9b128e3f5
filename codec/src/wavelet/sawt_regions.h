// SAWT regions (SAWT, Denis et al. 2010a as summarised
// by Satti et al. 2011; docs/REFERENCES.md): an octree over the
// base faces, split while a cell holds at least alpha vertices. Every
// quantity that decides membership is an integer the decoder holds too:
// cells live on the integer grid of the quantised base mesh (scaled by 3),
// a base face sits in the leaf containing 3 x its centroid (the sum of its
// corners' grid positions), and an odd vertex belongs to the region of the
// base face it lies in (on a base edge: the adjacent face of lower index).
#ifndef MESHWAVE_WAVELET_SAWT_REGIONS_H_
#define MESHWAVE_WAVELET_SAWT_REGIONS_H_

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"
#include "semiregular/base_face_of.h"
#include "wavelet/sawt_plan.h"

namespace meshwave {

inline constexpr uint32_t kDefaultSawtAlpha = 400;  // Satti et al. 2011, Fig. 4
// Octree depth at which cells stop splitting whatever they hold.
inline constexpr int kSawtMaxDepth = 20;

// Region of every odd vertex of level j.
std::vector<uint32_t> SawtOddVertexRegions(const SemiRegularHierarchy& h, int j,
                                           const std::vector<uint32_t>& face_region);

// Encoder: splits a cell while its base faces hold >= alpha odd vertices
// (of all levels), and records the split flags.
SawtRegions BuildSawtRegions(const SemiRegularHierarchy& h,
                             std::span<const IntVec3> base_grid, uint32_t alpha);

// Decoder: the same traversal with each undecided split read from
// `read_flag` (0 or 1); the flags are not stored in the result.
SawtRegions ReplaySawtRegions(const SemiRegularHierarchy& h,
                              std::span<const IntVec3> base_grid,
                              const std::function<int(int depth)>& read_flag);

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_SAWT_REGIONS_H_
