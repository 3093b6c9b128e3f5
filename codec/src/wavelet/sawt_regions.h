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

// (level, region) pairs that hold at least one odd vertex, in the order
// the stream codes them (the encoder's choices and the decoder's reading):
// levels finest first, regions in order. visit(j, region).
template <typename Visit>
void ForEachCodedSawtChoice(const SemiRegularHierarchy& h, const SawtRegions& regions,
                            Visit&& visit) {
  for (int j = h.levels() - 1; j >= 0; --j) {
    std::vector<char> used(regions.count, 0);
    for (uint32_t k = 0; k < h.subband_size(j); ++k) {
      used[regions.face_region[BaseFaceOf(h, j, k)]] = 1;
    }
    for (uint32_t r = 0; r < regions.count; ++r) {
      if (used[r]) visit(j, r);
    }
  }
}

}  // namespace meshwave

#endif  // MESHWAVE_WAVELET_SAWT_REGIONS_H_
