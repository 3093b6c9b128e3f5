// The SAWT filter choices in the stream header (docs/FORMAT.md section 9):
// the octree split flags, then one filter index per coded (level, region),
// in one arithmetic codeword with the adaptive models of
// wavelet/sawt_index_model.h, which the encoder (sawt_field_encoder.h)
// and the decoder (sawt_field_decoder.h) share.
#ifndef MESHWAVE_STREAM_SAWT_FIELD_DECODER_H_
#define MESHWAVE_STREAM_SAWT_FIELD_DECODER_H_

#include <memory>
#include <span>

#include "bitplane/coefficient_octree.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "wavelet/sawt_plan.h"

namespace meshwave {

// Safe on untrusted input: a codeword that ends early or gives another
// number of regions than the header states is refused.
Result<std::shared_ptr<const SawtPlan>> DecodeSawtChoices(
    const StreamHeader::SawtChoices& field, const SemiRegularHierarchy& h,
    std::span<const IntVec3> base_grid);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_SAWT_FIELD_DECODER_H_
