// The SAWT filter choices in the stream header (docs/FORMAT.md section 9):
// the octree split flags, then one filter index per coded (level, region),
// in one arithmetic codeword with the adaptive models of
// wavelet/sawt_index_model.h, which the encoder (sawt_field_encoder.h)
// and the decoder (sawt_field_decoder.h) share.
#ifndef MESHWAVE_STREAM_SAWT_FIELD_ENCODER_H_
#define MESHWAVE_STREAM_SAWT_FIELD_ENCODER_H_

#include <cstdint>
#include <span>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"
#include "meshwave/stream_header.h"
#include "wavelet/sawt_plan.h"

namespace meshwave {

// `base_grid`: the integer base positions the decoder will hold.
StreamHeader::SawtChoices EncodeSawtChoices(const SemiRegularHierarchy& h,
                                     std::span<const IntVec3> base_grid,
                                     const SawtPlan& plan, uint32_t alpha);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_SAWT_FIELD_ENCODER_H_
