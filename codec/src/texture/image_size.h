// The pixel size an encoded image's header declares (PNG's IHDR, JPEG's
// start-of-frame), read without decoding: what EncodeMesh checks a texture
// level against. Safe on untrusted bytes.
#ifndef MESHWAVE_TEXTURE_IMAGE_SIZE_H_
#define MESHWAVE_TEXTURE_IMAGE_SIZE_H_

#include <cstdint>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave {

struct ImageSize {
  uint32_t width = 0;
  uint32_t height = 0;
};

// The size of a PNG (mime "image/png"), baseline/progressive JPEG
// ("image/jpeg") or WebP ("image/webp"); kInvalidArgument when the bytes are not of that type or
// their header ends early.
Result<ImageSize> ReadImageSize(std::string_view bytes, std::string_view mime_type);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_IMAGE_SIZE_H_
