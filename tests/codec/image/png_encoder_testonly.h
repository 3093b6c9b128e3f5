// A PNG writer for the decoder tests: any colour type and bit depth, a
// palette and tRNS, Adam7 interlacing; filter 0 on every row, zlib for the
// data. Test-only: no checks of its input.
#ifndef MESHWAVE_TESTS_CODEC_IMAGE_PNG_ENCODER_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_IMAGE_PNG_ENCODER_TESTONLY_H_

#include <zlib.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace meshwave::testing {

struct PngSpec {
  uint32_t width = 1;
  uint32_t height = 1;
  int color_type = 2;  // 0 grey, 2 RGB, 3 palette, 4 grey+alpha, 6 RGBA
  int bit_depth = 8;
  bool interlaced = false;
  std::vector<std::array<uint8_t, 3>> palette;  // colour type 3
  std::string trns;                             // raw tRNS chunk data
  // Set: the image data (before zlib) is these bytes, whatever the size
  // says (a "decompression bomb" declares a size its data does not hold).
  bool raw_override = false;
  std::string raw;
};

inline int PngChannels(int color_type) {
  switch (color_type) {
    case 0:
    case 3:
      return 1;
    case 4:
      return 2;
    case 2:
      return 3;
    default:
      return 4;
  }
}

inline void PutBigEndian32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) {
    out += static_cast<char>((v >> shift) & 0xff);
  }
}

inline void PngChunk(std::string& out, const char* type,
                     const std::string& data) {
  PutBigEndian32(out, static_cast<uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  PutBigEndian32(out, static_cast<uint32_t>(
                          crc32(0, reinterpret_cast<const Bytef*>(body.data()),
                                static_cast<uInt>(body.size()))));
}

// `samples`: row-major, PngChannels(color_type) values per pixel, each below
// 2^bit_depth (palette indices for colour type 3).
inline std::string EncodePng(const PngSpec& spec,
                             const std::vector<uint16_t>& samples) {
  const int channels = PngChannels(spec.color_type);
  // The scanlines of one (sub)image: pixels (x0 + i*dx, y0 + j*dy).
  auto scanlines = [&](uint32_t x0, uint32_t y0, uint32_t dx, uint32_t dy) {
    std::string out;
    for (uint32_t y = y0; y < spec.height; y += dy) {
      out += '\0';  // filter: none
      uint32_t bits = 0;
      int filled = 0;
      for (uint32_t x = x0; x < spec.width; x += dx) {
        for (int c = 0; c < channels; ++c) {
          const uint16_t v =
              samples[(size_t{y} * spec.width + x) * channels + c];
          if (spec.bit_depth == 16) {
            out += static_cast<char>(v >> 8);
            out += static_cast<char>(v & 0xff);
          } else if (spec.bit_depth == 8) {
            out += static_cast<char>(v);
          } else {
            bits = (bits << spec.bit_depth) | v;
            filled += spec.bit_depth;
            if (filled == 8) {
              out += static_cast<char>(bits);
              bits = 0;
              filled = 0;
            }
          }
        }
      }
      if (filled > 0) out += static_cast<char>(bits << (8 - filled));
    }
    return out;
  };
  std::string raw = spec.raw;
  if (spec.raw_override) {
    // as given
  } else if (!spec.interlaced) {
    raw = scanlines(0, 0, 1, 1);
  } else {
    static constexpr std::array<std::array<uint32_t, 4>, 7> kPasses = {
        {{0, 0, 8, 8},
         {4, 0, 8, 8},
         {0, 4, 4, 8},
         {2, 0, 4, 4},
         {0, 2, 2, 4},
         {1, 0, 2, 2},
         {0, 1, 1, 2}}};
    for (const auto& p : kPasses) {
      if (p[0] < spec.width && p[1] < spec.height) {
        raw += scanlines(p[0], p[1], p[2], p[3]);
      }
    }
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(size, '\0');
  compress(reinterpret_cast<Bytef*>(packed.data()), &size,
           reinterpret_cast<const Bytef*>(raw.data()),
           static_cast<uLong>(raw.size()));
  packed.resize(size);

  std::string out = "\x89PNG\r\n\x1a\n";
  std::string ihdr;
  PutBigEndian32(ihdr, spec.width);
  PutBigEndian32(ihdr, spec.height);
  ihdr += static_cast<char>(spec.bit_depth);
  ihdr += static_cast<char>(spec.color_type);
  ihdr += '\0';  // compression
  ihdr += '\0';  // filter method
  ihdr += static_cast<char>(spec.interlaced ? 1 : 0);
  PngChunk(out, "IHDR", ihdr);
  if (!spec.palette.empty()) {
    std::string plte;
    for (const auto& rgb : spec.palette) {
      for (uint8_t c : rgb) plte += static_cast<char>(c);
    }
    PngChunk(out, "PLTE", plte);
  }
  if (!spec.trns.empty()) PngChunk(out, "tRNS", spec.trns);
  PngChunk(out, "IDAT", packed);
  PngChunk(out, "IEND", "");
  return out;
}

// An 8-bit RGBA PNG of `rgba` (width * height * 4 bytes).
inline std::string EncodeRgbaPng(uint32_t width, uint32_t height,
                                 const std::vector<uint8_t>& rgba) {
  PngSpec spec;
  spec.width = width;
  spec.height = height;
  spec.color_type = 6;
  return EncodePng(spec, std::vector<uint16_t>(rgba.begin(), rgba.end()));
}

// A decompression bomb: a small PNG whose header declares width x height
// grey pixels (its data a few zero bytes, never enough for them).
inline std::string BombPng(uint32_t width, uint32_t height) {
  PngSpec bomb;
  bomb.width = width;
  bomb.height = height;
  bomb.color_type = 0;
  bomb.raw_override = true;
  bomb.raw = std::string(64, '\0');
  return EncodePng(bomb, {});
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_IMAGE_PNG_ENCODER_TESTONLY_H_
