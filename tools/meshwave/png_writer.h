// A minimal PNG encoder (8-bit RGB, no interlace) on zlib, so that
// `meshwave render` needs no image library.
#ifndef MESHWAVE_TOOLS_PNG_WRITER_H_
#define MESHWAVE_TOOLS_PNG_WRITER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::cli {

// `rgb` holds width * height * 3 bytes, rows top to bottom. Returns the
// bytes of the PNG file. Errors: a size mismatch or a zlib failure.
Result<std::string> EncodePng(int width, int height, const std::vector<uint8_t>& rgb);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_PNG_WRITER_H_
