// Fuzz target: the texture decoders (PNG through libpng, JPEG through
// libjpeg-turbo, WebP through libwebp, by the sniffed format) on arbitrary
// bytes. They promise a Status for anything malformed or over the pixel
// limit, and an image of width * height RGBA pixels when they succeed.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_require_testonly.h"
#include "image/image_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  meshwave::ImageLimits limits;
  limits.max_pixels = 1 << 22;  // 16 MiB of RGBA: fuzzing speed, RSS cap
  const auto image = meshwave::DecodeImage(bytes, limits, "fuzz");
  if (!image.ok()) return 0;
  meshwave::fuzz::Require(image->width > 0 && image->height > 0,
                          "images are not empty");
  meshwave::fuzz::Require(
      image->rgba.size() == size_t{image->width} * image->height * 4,
      "images hold width * height * 4 bytes");
  meshwave::fuzz::Require(
      uint64_t{image->width} * image->height <= limits.max_pixels,
      "images respect the pixel limit");
  return 0;
}
