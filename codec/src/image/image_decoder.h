// Decoding of texture images (PNG, JPEG, WebP) to 8-bit RGBA, safe on
// untrusted bytes: the format is sniffed from the magic bytes (never from a
// file name), the dimensions are read from the header and checked against
// a pixel limit before any pixel buffer is allocated (a small file that
// declares a huge image, a "decompression bomb", is refused there), and
// truncated or corrupt data gives a ParseError rather than a partial image.
// The libraries' error paths are C-style (libpng's and libjpeg's longjmp):
// they are confined to small functions with no C++ objects to unwind.
#ifndef MESHWAVE_IMAGE_IMAGE_DECODER_H_
#define MESHWAVE_IMAGE_IMAGE_DECODER_H_

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

enum class ImageFormat { kUnknown, kPng, kJpeg, kWebp };

// The format the first bytes announce, kUnknown for anything else.
ImageFormat SniffImageFormat(std::string_view bytes);
// "image/png", "image/jpeg", "image/webp"; "" for kUnknown.
const char* ImageMimeType(ImageFormat format);
// A short description of unsupported bytes for messages: "GIF", "KTX2",
// "BMP", or "unknown (starts 3c 21 44 4f)".
std::string DescribeImageBytes(std::string_view bytes);

struct DecodedImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4 bytes, rows top to bottom
};

// Both checked from the header, before decoding.
struct ImageLimits {
  uint64_t max_pixels = uint64_t{64} << 20;  // per image
  // Decoded bytes (4 per pixel) this image may still take: what is left of
  // a budget shared by the images of one asset.
  uint64_t max_bytes = uint64_t{1} << 40;
};

// Decodes any supported format; kUnsupported for other formats (naming
// them) and for CMYK JPEG and animated WebP. `name` prefixes messages.
Result<DecodedImage> DecodeImage(std::string_view bytes,
                                 const ImageLimits& limits,
                                 std::string_view name);

// The per-format decoders (bytes must carry the format's magic).
// PNG: palette, grey, grey+alpha, RGB, RGBA at any bit depth, tRNS,
// interlaced; 16-bit samples are scaled to 8 bits. No gamma conversion:
// samples are kept as stored (textures hold data as well as colour).
Result<DecodedImage> DecodePng(std::string_view bytes,
                               const ImageLimits& limits,
                               std::string_view name);
// JPEG (libjpeg-turbo's TurboJPEG API): grey and YCbCr/RGB; CMYK and YCCK
// refused; a warning (such as a truncated scan) is an error; progressive
// files are limited to 500 scans (a scan flood costs time, not bytes).
Result<DecodedImage> DecodeJpeg(std::string_view bytes,
                                const ImageLimits& limits,
                                std::string_view name);
// WebP (libwebp): lossy and lossless, with or without alpha; animation
// refused.
Result<DecodedImage> DecodeWebp(std::string_view bytes,
                                const ImageLimits& limits,
                                std::string_view name);

// The shared pixel-limit check: kUnsupported naming the size and the
// limit (zero width or height: ParseError).
Status CheckImageSize(uint64_t width, uint64_t height,
                      const ImageLimits& limits, std::string_view name,
                      const char* format);

}  // namespace meshwave

#endif  // MESHWAVE_IMAGE_IMAGE_DECODER_H_
