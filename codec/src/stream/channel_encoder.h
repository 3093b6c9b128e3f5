// The encoder of a stream's colour channel (docs/FORMAT.md 2.3): the
// colours of the prepared mesh's vertices in YCoCg, lifted by the
// geometry's transform without local frames, base values into the header,
// subbands quantised and coded as the geometry's are (stream/
// signal_encoder.h), with steps and weights of their own.
#ifndef MESHWAVE_STREAM_CHANNEL_ENCODER_H_
#define MESHWAVE_STREAM_CHANNEL_ENCODER_H_

#include <vector>

#include "bitplane/subband_layout.h"
#include "meshwave/encoder.h"
#include "meshwave/status.h"
#include "stream.pb.h"
#include "stream/signal_encoder.h"
#include "stream/stream_preparation.h"

namespace meshwave {

struct EncodedChannel {
  proto::Channel header;  // kind, base values, quantizers, rd weight
  CodedSignal coded;      // per subband, its packets (never split)
  // Per subband, the weighted energy of its coefficients: its chain's
  // distortion with none of its packets (squared RGB error, peak 1).
  std::vector<double> chain_start;
};

// Codes `colors` (linear RGB per vertex of `mesh`, the prepared stream's
// mesh, in its order) with the step 2^-options.color_precision and the
// subbands' `layouts`.
// kInvalidArgument when the count differs from the mesh's vertices, a
// colour is not finite, or color_precision or color_rd_weight are out of
// range.
Result<EncodedChannel> EncodeColorChannel(const PreparedStream& prepared,
                                          const SemiRegularMesh& mesh,
                                          const std::vector<Vec3>& colors,
                                          const std::vector<std::vector<SubbandLayout>>& layouts,
                                          const EncodeOptions& options);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_CHANNEL_ENCODER_H_
