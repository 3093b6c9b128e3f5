#include "stream/sawt_field_decoder.h"

#include <string>

#include "entropy/arithmetic_decoder.h"
#include "stream/stream_format.h"
#include "wavelet/sawt_index_model.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {

Result<std::shared_ptr<const SawtPlan>> DecodeSawtChoices(
    const StreamHeader::SawtChoices& field, const SemiRegularHierarchy& h,
    std::span<const IntVec3> base_grid) {
  if (Crc32c(field.coded) != field.crc32c) {
    return ParseError("header: SAWT filter choices are corrupt (the CRC-32C of their " +
                      std::to_string(field.coded.size()) + " bytes does not match)");
  }
  ArithmeticDecoder decoder(field.coded);
  SawtSideModel model;
  auto plan = std::make_shared<SawtPlan>();
  plan->regions = ReplaySawtRegions(
      h, base_grid, [&](int depth) { return decoder.Decode(model.SplitContext(depth)); });
  if (plan->regions.count != field.region_count) {
    return ParseError("header: SAWT filter choices are corrupt (their split flags give " +
                      std::to_string(plan->regions.count) + " regions, the header says " +
                      std::to_string(field.region_count) + ")");
  }
  plan->filters.assign(h.levels(), std::vector<SawtFilter>(plan->regions.count,
                                                           SawtFilter::kButterfly));
  ForEachCodedSawtChoice(h, plan->regions, [&](int j, uint32_t r) {
    plan->filters[j][r] = model.DecodeIndex(decoder);
  });
  if (decoder.overrun()) {
    return ParseError("header: SAWT filter choices are truncated or corrupt (the codeword of " +
                      std::to_string(field.coded.size()) +
                      " bytes ends before the last filter index)");
  }
  return std::shared_ptr<const SawtPlan>(std::move(plan));
}

}  // namespace meshwave
