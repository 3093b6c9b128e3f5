// Constants and conversions the stream writer and readers share.
#ifndef MESHWAVE_STREAM_STREAM_FORMAT_H_
#define MESHWAVE_STREAM_STREAM_FORMAT_H_

#include <boost/crc.hpp>
#include <cstdint>
#include <string_view>

#include "meshwave/status.h"
#include "meshwave/wavelet.h"
#include "stream.pb.h"

namespace meshwave {

inline constexpr uint32_t kFormatVersion = 4;  // 3: Transform.sawt; 4: compact packet index
inline constexpr char kContainerMagic[4] = {'M', 'W', 'V', '1'};
// Limits on what a stream may ask a decoder to build.
inline constexpr uint32_t kMaxBaseVertices = 1u << 24;
inline constexpr uint32_t kMaxHeaderBytes = 64u << 20;

// CRC-32C (Castagnoli) of a byte string; the SAWT field's check.
inline uint32_t Crc32c(std::string_view bytes) {
  boost::crc_optimal<32, 0x1EDC6F41, 0xFFFFFFFF, 0xFFFFFFFF, true, true> crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return crc.checksum();
}

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

inline Result<TransformSettings> FromProto(const proto::Transform& t) {
  TransformSettings s;
  switch (t.predictor()) {
    case proto::PREDICTOR_LINEAR: s.predictor = Predictor::kLinear; break;
    case proto::PREDICTOR_BUTTERFLY: s.predictor = Predictor::kButterfly; break;
    case proto::PREDICTOR_LOOP: s.predictor = Predictor::kLoop; break;
    case proto::PREDICTOR_SAWT: s.predictor = Predictor::kSawt; break;
    default: return ParseError("unknown predictor " + std::to_string(t.predictor()));
  }
  switch (t.update()) {
    case proto::UPDATE_NONE: s.update = UpdateWeights::kNone; break;
    case proto::UPDATE_CONSTANT: s.update = UpdateWeights::kConstant; break;
    case proto::UPDATE_VALENCE: s.update = UpdateWeights::kValence; break;
    default: return ParseError("unknown update weights " + std::to_string(t.update()));
  }
  s.frames = t.local_frames() ? FrameMode::kLocal : FrameMode::kGlobal;
  // The SAWT choices need the decoded base mesh: the decoders read them
  // (stream/sawt_field.h) once it is built.
  if (s.predictor == Predictor::kSawt && !t.has_sawt()) {
    return ParseError("header: SAWT transform without its filter choices");
  }
  if (s.predictor != Predictor::kSawt && t.has_sawt()) {
    return ParseError("header: SAWT filter choices with another predictor");
  }
  return s;
}

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_STREAM_FORMAT_H_
