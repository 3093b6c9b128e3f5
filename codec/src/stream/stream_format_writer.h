// The header fields the encoders write from their settings (the readers'
// side is stream/stream_format.h).
#ifndef MESHWAVE_STREAM_STREAM_FORMAT_WRITER_H_
#define MESHWAVE_STREAM_STREAM_FORMAT_WRITER_H_

#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/wavelet.h"
#include "stream.pb.h"

namespace meshwave {

inline void ToProto(const TransformSettings& s, int levels, proto::Transform& t) {
  t.set_predictor(s.predictor == Predictor::kLinear ? proto::PREDICTOR_LINEAR
                  : s.predictor == Predictor::kLoop ? proto::PREDICTOR_LOOP
                  : s.predictor == Predictor::kSawt ? proto::PREDICTOR_SAWT
                                                    : proto::PREDICTOR_BUTTERFLY);
  t.set_update(s.update == UpdateWeights::kNone       ? proto::UPDATE_NONE
               : s.update == UpdateWeights::kValence ? proto::UPDATE_VALENCE
                                                     : proto::UPDATE_CONSTANT);
  t.set_local_frames(s.frames == FrameMode::kLocal);
  t.set_levels(static_cast<uint32_t>(levels));
}

void ToProto(const StreamHeader::BaseMesh& base, proto::BaseMesh& out);
void ToProto(const StreamHeader::SawtChoices& sawt, proto::SawtChoices& out);

// The encoder builds its header with protobuf (whose serialization the
// stream's bytes are) and hands it out as the decoder reads it.
// Errors: a name that is not UTF-8 (protobuf writes it, nobody reads it).
Result<StreamHeader> ToStreamHeader(const proto::StreamHeader& header);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_STREAM_FORMAT_WRITER_H_
