#include "stream/channel_base_decoder.h"

#include <cmath>
#include <string>

namespace meshwave {

Result<std::vector<Vec3>> DecodeChannelBase(const StreamHeader::Channel& channel,
                                            uint32_t base_vertices) {
  if (!(channel.base_step > 0) || !std::isfinite(channel.base_step)) {
    return ParseError("header: a channel's base step is not finite and positive");
  }
  const std::string& bytes = channel.base;
  // Each value takes 1 to 5 bytes: refuse a count the bytes cannot hold
  // before allocating for it.
  const uint64_t values = 3 * uint64_t{base_vertices};
  if (bytes.size() < values || bytes.size() > 5 * values) {
    return ParseError("header: a channel's base values take " + std::to_string(bytes.size()) +
                      " bytes, which cannot hold " + std::to_string(values) +
                      " values (3 per base vertex)");
  }
  std::vector<Vec3> out(base_vertices);
  size_t at = 0;
  for (uint64_t i = 0; i < values; ++i) {
    uint64_t u = 0;
    for (int shift = 0;; shift += 7) {
      if (at == bytes.size()) {
        return ParseError("header: a channel's base values end inside value " +
                          std::to_string(i) + " of " + std::to_string(values));
      }
      const auto byte = static_cast<uint8_t>(bytes[at++]);
      u |= uint64_t{byte & 0x7fu} << shift;
      if ((byte & 0x80) == 0) break;
      if (shift == 28) {
        return ParseError("header: a channel's base value " + std::to_string(i) +
                          " is longer than 5 bytes");
      }
    }
    if (u > 0xffffffffu) {
      return ParseError("header: a channel's base value " + std::to_string(i) +
                        " exceeds 32 bits");
    }
    // Zigzag: 0, -1, 1, -2, ... as 0, 1, 2, 3, ...
    const int64_t q = (u & 1) ? -static_cast<int64_t>((u + 1) >> 1) : static_cast<int64_t>(u >> 1);
    out[i / 3][static_cast<int>(i % 3)] = static_cast<double>(q) * channel.base_step;
  }
  if (at != bytes.size()) {
    return ParseError("header: " + std::to_string(bytes.size() - at) +
                      " bytes after a channel's base values");
  }
  return out;
}

}  // namespace meshwave
