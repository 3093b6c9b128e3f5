// Real PNG files of any size for tests: a solid RGB image, its zlib stream
// made of stored (uncompressed) deflate blocks, so no compressor is needed
// and every decoder and validator reads it.
#ifndef MESHWAVE_TESTS_CODEC_TEXTURE_PNG_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_TEXTURE_PNG_TESTONLY_H_

#include <algorithm>
#include <cstdint>
#include <string>

namespace meshwave::testing {

namespace png_internal {

inline void BigEndian32(std::string& out, uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>(v >> s));
}

// CRC-32 (ISO 3309, as PNG's chunks use), bit by bit: test data is small.
inline uint32_t Crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (char ch : bytes) {
    c ^= static_cast<uint8_t>(ch);
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

inline void Chunk(std::string& out, const char* type, const std::string& data) {
  BigEndian32(out, static_cast<uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  BigEndian32(out, Crc32(body));
}

}  // namespace png_internal

inline std::string SolidPng(uint32_t width, uint32_t height, uint8_t r, uint8_t g, uint8_t b) {
  using namespace png_internal;
  std::string raw;  // per row: filter 0, then RGB
  for (uint32_t y = 0; y < height; ++y) {
    raw.push_back(0);
    for (uint32_t x = 0; x < width; ++x) raw += {static_cast<char>(r), static_cast<char>(g),
                                                 static_cast<char>(b)};
  }
  std::string z = "\x78\x01";
  for (size_t at = 0; at == 0 || at < raw.size(); at += 65535) {
    const size_t n = std::min<size_t>(65535, raw.size() - at);
    z.push_back(at + n == raw.size() ? 1 : 0);
    z += {static_cast<char>(n & 0xff), static_cast<char>(n >> 8),
          static_cast<char>(~n & 0xff), static_cast<char>((~n >> 8) & 0xff)};
    z += raw.substr(at, n);
  }
  uint32_t a = 1, s = 0;  // Adler-32
  for (char ch : raw) {
    a = (a + static_cast<uint8_t>(ch)) % 65521;
    s = (s + a) % 65521;
  }
  BigEndian32(z, s << 16 | a);
  std::string ihdr;
  BigEndian32(ihdr, width);
  BigEndian32(ihdr, height);
  ihdr += {8, 2, 0, 0, 0};  // 8-bit RGB, deflate, no filter method, not interlaced
  std::string out("\x89PNG\r\n\x1a\n", 8);
  Chunk(out, "IHDR", ihdr);
  Chunk(out, "IDAT", z);
  Chunk(out, "IEND", "");
  return out;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_TEXTURE_PNG_TESTONLY_H_
