// Reads back the PNGs meshwave writes (8-bit RGB, filter 0 rows): checks
// the signature, every chunk's CRC and the IHDR, inflates the IDAT data
// with zlib and undoes the row filters, so tests compare real pixels.
#ifndef MESHWAVE_TESTS_E2E_PNG_READER_TESTONLY_H_
#define MESHWAVE_TESTS_E2E_PNG_READER_TESTONLY_H_

#include <zlib.h>

#include <cstdint>
#include <string>
#include <vector>

namespace meshwave::testing {

struct DecodedPng {
  std::string error;  // empty when the file was read
  uint32_t width = 0, height = 0;
  int bit_depth = 0, colour_type = 0, interlace = 0;
  std::vector<uint8_t> rgb;  // width * height * 3, rows top to bottom
};

inline uint32_t Get32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = v << 8 | static_cast<uint8_t>(s[at + i]);
  return v;
}

inline DecodedPng ReadPng(const std::string& bytes) {
  DecodedPng png;
  if (bytes.size() < 8 || bytes.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) != 0) {
    png.error = "no PNG signature";
    return png;
  }
  std::string idat;
  bool ended = false;
  for (size_t at = 8; at < bytes.size() && !ended;) {
    if (at + 12 > bytes.size()) {
      png.error = "truncated chunk";
      return png;
    }
    const uint32_t length = Get32(bytes, at);
    if (at + 12 + length > bytes.size()) {
      png.error = "chunk longer than the file";
      return png;
    }
    const std::string type = bytes.substr(at + 4, 4);
    const std::string body = bytes.substr(at + 4, 4 + length);
    const uint32_t crc = static_cast<uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
    if (crc != Get32(bytes, at + 8 + length)) {
      png.error = "bad CRC in " + type;
      return png;
    }
    const std::string data = body.substr(4);
    if (type == "IHDR") {
      if (length != 13) {
        png.error = "IHDR of " + std::to_string(length) + " bytes";
        return png;
      }
      png.width = Get32(data, 0);
      png.height = Get32(data, 4);
      png.bit_depth = static_cast<uint8_t>(data[8]);
      png.colour_type = static_cast<uint8_t>(data[9]);
      png.interlace = static_cast<uint8_t>(data[12]);
    } else if (type == "IDAT") {
      idat += data;
    } else if (type == "IEND") {
      ended = true;
    }
    at += 12 + length;
  }
  if (!ended || png.width == 0 || png.height == 0) {
    png.error = "no IEND or no IHDR";
    return png;
  }
  if (png.bit_depth != 8 || png.colour_type != 2 || png.interlace != 0) {
    png.error = "not 8-bit RGB without interlace";
    return png;
  }
  const size_t row = static_cast<size_t>(png.width) * 3;
  std::vector<uint8_t> raw((row + 1) * png.height);
  uLongf size = static_cast<uLongf>(raw.size());
  if (uncompress(raw.data(), &size, reinterpret_cast<const Bytef*>(idat.data()),
                 static_cast<uLong>(idat.size())) != Z_OK ||
      size != raw.size()) {
    png.error = "IDAT does not inflate to the image size";
    return png;
  }
  png.rgb.reserve(row * png.height);
  for (uint32_t y = 0; y < png.height; ++y) {
    if (raw[y * (row + 1)] != 0) {  // meshwave writes filter type 0 only
      png.error = "row filter " + std::to_string(raw[y * (row + 1)]);
      return png;
    }
    png.rgb.insert(png.rgb.end(), raw.begin() + y * (row + 1) + 1, raw.begin() + (y + 1) * (row + 1));
  }
  return png;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_E2E_PNG_READER_TESTONLY_H_
