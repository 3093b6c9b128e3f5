// Encoding of 8-bit images for the texture maps the encoder bakes: JPEG
// through libjpeg-turbo's TurboJPEG API, PNG through libpng. The inputs are
// the encoder's own pixels, not untrusted bytes; sizes are still checked so
// a wrong buffer gives a Status rather than a read past its end.
#ifndef MESHWAVE_IMAGE_IMAGE_ENCODER_H_
#define MESHWAVE_IMAGE_IMAGE_ENCODER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

// Pixels to encode: width * height * channels bytes, rows top to bottom,
// channels 3 (RGB) or 4 (RGBA).
struct ImageView {
  const uint8_t* pixels = nullptr;
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 3;
};

struct JpegEncodeOptions {
  int quality = 90;  // 1..100
  // Chroma subsampled 2x2 (4:2:0) for colour, where the eye forgives it;
  // 4:4:4 for data (normals, roughness), whose channels are independent.
  bool subsample_chroma = true;
};

// A baseline JPEG of the image's RGB (alpha, when present, is dropped).
// kInvalidArgument for an empty image, a channel count other than 3 or 4
// or a quality outside 1..100; kInternal when libjpeg-turbo fails.
Result<std::string> EncodeJpeg(const ImageView& image, const JpegEncodeOptions& options = {});

// A lossy WebP of the image (libwebp's default preset at `quality`, 0..100;
// alpha, when present, coded losslessly beside it). Errors as EncodeJpeg's,
// and kInvalidArgument beyond WebP's 16383 pixels a side.
Result<std::string> EncodeWebp(const ImageView& image, int quality);

// A PNG of the image, RGB or RGBA as given, 8 bits a sample, zlib level
// `compression` (0..9). Errors as EncodeJpeg's.
Result<std::string> EncodePng(const ImageView& image, int compression = 6);

}  // namespace meshwave

#endif  // MESHWAVE_IMAGE_IMAGE_ENCODER_H_
