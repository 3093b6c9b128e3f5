#include "texture/image_size.h"

#include <string>

namespace meshwave {
namespace {

uint32_t BigEndian(std::string_view b, size_t at, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = v << 8 | static_cast<uint8_t>(b[at + static_cast<size_t>(i)]);
  return v;
}

Result<ImageSize> PngSize(std::string_view b) {
  // Signature, then the IHDR chunk first: length, "IHDR", width, height.
  static constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
  if (b.size() < 24 || b.substr(0, 8) != kSignature || b.substr(12, 4) != "IHDR") {
    return InvalidArgument("not a PNG (no signature and IHDR chunk)");
  }
  return ImageSize{BigEndian(b, 16, 4), BigEndian(b, 20, 4)};
}

Result<ImageSize> JpegSize(std::string_view b) {
  if (b.size() < 4 || static_cast<uint8_t>(b[0]) != 0xff || static_cast<uint8_t>(b[1]) != 0xd8) {
    return InvalidArgument("not a JPEG (no start-of-image marker)");
  }
  size_t at = 2;
  while (at + 4 <= b.size()) {
    if (static_cast<uint8_t>(b[at]) != 0xff) return InvalidArgument("JPEG: a segment without a marker");
    const auto marker = static_cast<uint8_t>(b[at + 1]);
    if (marker == 0xff) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd9)) {  // no length
      at += 2;
      continue;
    }
    const uint32_t length = BigEndian(b, at + 2, 2);
    // Start of frame: every SOFn but DHT (c4), JPG (c8) and DAC (cc).
    const bool frame = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 &&
                       marker != 0xcc;
    if (frame) {
      if (length < 7 || at + 9 > b.size()) return InvalidArgument("JPEG: a short frame header");
      return ImageSize{BigEndian(b, at + 7, 2), BigEndian(b, at + 5, 2)};
    }
    if (length < 2) return InvalidArgument("JPEG: a segment shorter than its length field");
    at += 2 + length;
  }
  return InvalidArgument("JPEG: no frame header");
}

uint32_t LittleEndian(std::string_view b, size_t at, int bytes) {
  uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) {
    v = v << 8 | static_cast<uint8_t>(b[at + static_cast<size_t>(i)]);
  }
  return v;
}

// RIFF "WEBP" and its first chunk: VP8 (lossy: the key frame's 14-bit
// sizes), VP8L (lossless: 14-bit sizes minus one) or VP8X (extended: the
// canvas's 24-bit sizes minus one), as libwebp's container spec lays out.
Result<ImageSize> WebpSize(std::string_view b) {
  if (b.size() < 30 || b.substr(0, 4) != "RIFF" || b.substr(8, 4) != "WEBP") {
    return InvalidArgument("not a WebP (no RIFF WEBP header)");
  }
  const std::string_view chunk = b.substr(12, 4);
  if (chunk == "VP8 ") {
    if (static_cast<uint8_t>(b[23]) != 0x9d || static_cast<uint8_t>(b[24]) != 0x01 ||
        static_cast<uint8_t>(b[25]) != 0x2a) {
      return InvalidArgument("WebP: a VP8 chunk without a key frame's start code");
    }
    return ImageSize{LittleEndian(b, 26, 2) & 0x3fff, LittleEndian(b, 28, 2) & 0x3fff};
  }
  if (chunk == "VP8L") {
    if (static_cast<uint8_t>(b[20]) != 0x2f) return InvalidArgument("WebP: a VP8L chunk without its signature");
    const uint32_t bits = LittleEndian(b, 21, 4);
    return ImageSize{(bits & 0x3fff) + 1, ((bits >> 14) & 0x3fff) + 1};
  }
  if (chunk == "VP8X") return ImageSize{LittleEndian(b, 24, 3) + 1, LittleEndian(b, 27, 3) + 1};
  return InvalidArgument("WebP: an unknown first chunk");
}

}  // namespace

Result<ImageSize> ReadImageSize(std::string_view bytes, std::string_view mime_type) {
  if (mime_type == "image/png") return PngSize(bytes);
  if (mime_type == "image/jpeg") return JpegSize(bytes);
  if (mime_type == "image/webp") return WebpSize(bytes);
  return InvalidArgument("image type \"" + std::string(mime_type) +
                         "\" (image/jpeg, image/png or image/webp)");
}

}  // namespace meshwave
