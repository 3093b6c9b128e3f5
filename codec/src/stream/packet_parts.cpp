#include "meshwave/packet_parts.h"

#include "core/protobuf_wire.h"

namespace meshwave {

std::string JoinPacketParts(std::span<const std::string> parts) {
  std::string out;
  for (size_t p = 0; p + 1 < parts.size(); ++p) PutVarint(out, parts[p].size());
  for (const std::string& part : parts) out += part;
  return out;
}

Result<std::vector<std::string_view>> SplitPacketParts(std::string_view payload,
                                                       uint32_t count) {
  std::vector<std::string_view> out;
  if (count == 0) return ParseError("a split packet of no parts");
  std::vector<uint64_t> lengths;
  lengths.reserve(count - 1);
  size_t at = 0;
  for (uint32_t p = 0; p + 1 < count; ++p) {
    uint64_t v = 0;
    for (int shift = 0;; shift += 7) {
      if (at >= payload.size() || shift > 28) {
        return ParseError("part table of a split packet is truncated or malformed (part " +
                          std::to_string(p) + " of " + std::to_string(count) + ")");
      }
      const auto byte = static_cast<uint8_t>(payload[at++]);
      v |= static_cast<uint64_t>(byte & 0x7f) << shift;
      if ((byte & 0x80) == 0) break;
    }
    lengths.push_back(v);
  }
  out.reserve(count);
  for (uint64_t length : lengths) {
    if (length > payload.size() - at) {
      return ParseError("parts of a split packet overrun its " + std::to_string(payload.size()) +
                        " bytes");
    }
    out.push_back(payload.substr(at, length));
    at += length;
  }
  out.push_back(payload.substr(at));
  return out;
}

}  // namespace meshwave
