// WebP through libwebp's simple decoding API.
#include <webp/decode.h>

#include <string>

#include "image/image_decoder.h"

namespace meshwave {
namespace {

const char* Vp8StatusText(VP8StatusCode code) {
  switch (code) {
    case VP8_STATUS_OK:
      return "ok";
    case VP8_STATUS_OUT_OF_MEMORY:
      return "out of memory";
    case VP8_STATUS_INVALID_PARAM:
      return "invalid parameter";
    case VP8_STATUS_BITSTREAM_ERROR:
      return "corrupt bitstream";
    case VP8_STATUS_UNSUPPORTED_FEATURE:
      return "unsupported feature";
    case VP8_STATUS_SUSPENDED:
      return "suspended";
    case VP8_STATUS_USER_ABORT:
      return "aborted";
    case VP8_STATUS_NOT_ENOUGH_DATA:
      return "the file ends early (truncated)";
  }
  return "unknown error";
}

}  // namespace

Result<DecodedImage> DecodeWebp(std::string_view bytes,
                                const ImageLimits& limits,
                                std::string_view name) {
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  WebPBitstreamFeatures features;
  const VP8StatusCode status = WebPGetFeatures(data, bytes.size(), &features);
  if (status != VP8_STATUS_OK) {
    return ParseError(std::string(name) +
                      ": WebP header: " + Vp8StatusText(status));
  }
  if (features.has_animation) {
    return Status(StatusCode::kUnsupported,
                  std::string(name) + ": animated WebP is not supported");
  }
  if (features.width <= 0 || features.height <= 0) {
    return ParseError(std::string(name) + ": WebP declares an empty image");
  }
  MW_RETURN_IF_ERROR(CheckImageSize(static_cast<uint64_t>(features.width),
                                    static_cast<uint64_t>(features.height),
                                    limits, name, "WebP"));
  DecodedImage image;
  image.width = static_cast<uint32_t>(features.width);
  image.height = static_cast<uint32_t>(features.height);
  image.rgba.resize(size_t{image.width} * image.height * 4);
  if (WebPDecodeRGBAInto(data, bytes.size(), image.rgba.data(),
                         image.rgba.size(),
                         static_cast<int>(image.width * 4)) == nullptr) {
    return ParseError(std::string(name) +
                      ": WebP image data is corrupt or truncated");
  }
  return image;
}

}  // namespace meshwave
