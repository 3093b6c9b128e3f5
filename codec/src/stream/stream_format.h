// Constants and conversions the stream writer and readers share.
#ifndef MESHWAVE_STREAM_STREAM_FORMAT_H_
#define MESHWAVE_STREAM_STREAM_FORMAT_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "core/crc.h"  // Crc32c: the SAWT field's check
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/stream_limits.h"  // kMaxHeaderBytes, kMaxStreamLevels
#include "meshwave/wavelet.h"

namespace meshwave {

// The version this build writes (meshwave/stream_header.h).
inline constexpr uint32_t kFormatVersion = kStreamFormatVersion;
// The oldest version it reads. Version 9 is version 10 without the
// original layer, version 8 is version 9 without textures,
// version 7 is version 8 without channels,
// version 6 is version 7 without precincts
// (docs/FORMAT.md 2.2): kept readable so that a catalog written by the
// previous release is served while `meshwave-server reencode` brings it
// to this one (docs/DEPLOY.md, "Upgrades"). Each format change keeps the
// previous version readable the same way.
inline constexpr uint32_t kOldestReadFormatVersion = 6;

// The one check of a header's format version: one this build reads
// (kUnsupported, naming both, otherwise), and nothing an older version's
// stream cannot hold (kParseError).
inline Status CheckFormatVersion(const StreamHeader& h) {
  if (h.format_version < kOldestReadFormatVersion || h.format_version > kFormatVersion) {
    return Status(StatusCode::kUnsupported,
                  "format version " + std::to_string(h.format_version) +
                      " (this build reads versions " + std::to_string(kOldestReadFormatVersion) +
                      " to " + std::to_string(kFormatVersion) + ")");
  }
  if (h.format_version == 6 &&
      (h.packets.precinct_coefficients != 0 || !h.packets.split_planes.empty())) {
    return ParseError("header: a version-6 stream with precincts (they came with version 7)");
  }
  if (h.format_version < 8 && !h.channels.empty()) {
    return ParseError("header: a version-" + std::to_string(h.format_version) +
                      " stream with channels (they came with version 8)");
  }
  if (h.format_version < 9 && h.texture) {
    return ParseError("header: a version-" + std::to_string(h.format_version) +
                      " stream with a texture (textures came with version 9)");
  }
  if (h.format_version < 10 && h.original) {
    return ParseError("header: a version-" + std::to_string(h.format_version) +
                      " stream with an original layer (it came with version 10)");
  }
  if (h.format_version < 11 && h.texture) {
    for (const StreamHeader::Texture::Map& map : h.texture->maps) {
      if (map.mime_type == "image/webp") {
        return ParseError("header: a version-" + std::to_string(h.format_version) +
                          " stream with a WebP texture (WebP came with version 11)");
      }
    }
  }
  return Status::Ok();
}
inline constexpr char kContainerMagic[4] = {'M', 'W', 'V', '1'};
// StreamHeader.present's field number in stream.proto, for the decoder
// library, which has no generated code (stream_format_writer.cpp asserts it
// equals the generated constant).
inline constexpr uint32_t kHeaderPresentField = 14;
// Limits on what a stream may ask a decoder to build.
inline constexpr uint32_t kMaxBaseVertices = 1u << 24;
inline constexpr uint32_t kMaxBaseRefinementPlanes = 20;
// Channels a stream may have: one of each kind.
inline constexpr uint32_t kMaxChannels = 1;
// The original layer's positions packets after the coarse one.
inline constexpr uint32_t kMaxOriginalRefinementPlanes = 8;

inline Result<TransformSettings> ReadTransformSettings(const StreamHeader::Transform& t) {
  TransformSettings s;
  switch (t.predictor) {
    case StreamPredictor::kLinear: s.predictor = Predictor::kLinear; break;
    case StreamPredictor::kButterfly: s.predictor = Predictor::kButterfly; break;
    case StreamPredictor::kLoop: s.predictor = Predictor::kLoop; break;
    case StreamPredictor::kSawt: s.predictor = Predictor::kSawt; break;
    default:
      return ParseError("unknown predictor " + std::to_string(static_cast<int32_t>(t.predictor)));
  }
  switch (t.update) {
    case StreamUpdate::kNone: s.update = UpdateWeights::kNone; break;
    case StreamUpdate::kConstant: s.update = UpdateWeights::kConstant; break;
    case StreamUpdate::kValence: s.update = UpdateWeights::kValence; break;
    default:
      return ParseError("unknown update weights " + std::to_string(static_cast<int32_t>(t.update)));
  }
  s.frames = t.local_frames ? FrameMode::kLocal : FrameMode::kGlobal;
  // The SAWT choices need the decoded base mesh: the decoders read them
  // (stream/sawt_field_decoder.h) once it is built.
  if (s.predictor == Predictor::kSawt && !t.sawt) {
    return ParseError("header: SAWT transform without its filter choices");
  }
  if (s.predictor != Predictor::kSawt && t.sawt) {
    return ParseError("header: SAWT filter choices with another predictor");
  }
  return s;
}

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_STREAM_FORMAT_H_
