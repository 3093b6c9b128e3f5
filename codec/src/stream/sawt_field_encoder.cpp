#include "stream/sawt_field_encoder.h"

#include "entropy/arithmetic_encoder.h"
#include "stream/stream_format.h"
#include "wavelet/sawt_index_model.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {

StreamHeader::SawtChoices EncodeSawtChoices(const SemiRegularHierarchy& h,
                                     std::span<const IntVec3> base_grid,
                                     const SawtPlan& plan, uint32_t alpha) {
  ArithmeticEncoder encoder;
  SawtSideModel model;
  size_t next = 0;
  // Replaying the flags gives each its octree depth (its context).
  ReplaySawtRegions(h, base_grid, [&](int depth) {
    const int bit = next < plan.regions.split_flags.size() ? plan.regions.split_flags[next++] : 0;
    encoder.Encode(bit, model.SplitContext(depth));
    return bit;
  });
  ForEachCodedSawtChoice(h, plan.regions, [&](int j, uint32_t r) {
    model.ForEachIndexBit(plan.filters[j][r],
                          [&](int bit, BinaryContext& ctx) { encoder.Encode(bit, ctx); });
  });
  StreamHeader::SawtChoices field;
  field.alpha = alpha;
  field.region_count = plan.regions.count;
  field.coded = encoder.Finish();
  field.crc32c = Crc32c(field.coded);
  return field;
}

}  // namespace meshwave
