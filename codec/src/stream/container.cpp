#include "meshwave/container.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_set>

#include "stream/packet_index.h"
#include "stream/stream_format.h"
#include "stream/varint.h"

namespace meshwave {
namespace {

void PutU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

uint32_t GetU32(std::string_view b) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<uint8_t>(b[i]);
  return v;
}

}  // namespace

uint64_t PresentFieldSize(uint64_t id_bytes) {
  return id_bytes == 0 ? 0 : 1 + VarintSize(id_bytes) + id_bytes;
}

uint64_t ContainerSize(const StreamHeader& header,
                       std::span<const uint32_t> ids) {
  // Sizes are added, not serialized: this runs once per packet when a
  // budget is fitted.
  uint64_t size = 8 + header.bytes_without_present.size();
  uint64_t id_bytes = 0;
  for (uint32_t id : ids) {
    id_bytes += VarintSize(id);
    size += header.packets.length[id];
  }
  return size + PresentFieldSize(id_bytes);
}

std::string SerializeContainerHead(const StreamHeader& header,
                                   std::span<const uint32_t> ids) {
  return SerializeContainerHead(header.bytes_without_present, ids);
}

std::string SerializeContainerHead(std::string_view header_without_present,
                                   std::span<const uint32_t> ids) {
  // `present` (field 14, packed varints) has the highest field number, so
  // protobuf's own serializer would write it last: appending it gives the
  // same bytes as serializing the header with the list set.
  constexpr uint32_t kPresentTag = 14 << 3 | 2;  // field 14, length-delimited
  std::string present;
  for (uint32_t id : ids) PutVarint(present, id);
  std::string field;
  if (!ids.empty()) {
    PutVarint(field, kPresentTag);
    PutVarint(field, present.size());
  }
  std::string out(kContainerMagic, 4);
  PutU32(out, static_cast<uint32_t>(header_without_present.size() + field.size() +
                                    present.size()));
  out.reserve(out.size() + header_without_present.size() + field.size() + present.size());
  out.append(header_without_present);
  out += field;
  out += present;
  return out;
}

std::vector<double> EstimatedPsnrCurve(const StreamHeader& header,
                                       std::span<const uint32_t> order) {
  // Mirrors ProgressiveDecoder::EstimatedPsnr, packet by packet.
  double diagonal = 0;
  for (size_t a = 0; a < 3 && a < header.bbox_min.size() && a < header.bbox_max.size(); ++a) {
    const double d = header.bbox_max[a] - header.bbox_min[a];
    diagonal += d * d;
  }
  diagonal = std::sqrt(diagonal);
  const double vertices = static_cast<double>(std::max<uint64_t>(header.vertices, 1));
  auto psnr = [&](double distortion) {
    const double mse = std::max(distortion, 0.0) / vertices;
    if (mse <= 0) return std::numeric_limits<double>::infinity();
    return 20 * std::log10(diagonal / std::sqrt(mse));
  };
  std::vector<double> out;
  out.reserve(order.size() + 1);
  const DistortionEstimates estimates = ReadDistortionIndex(header, PacketChains(header));
  std::vector<double> now = estimates.chain_start;
  double distortion = estimates.Estimate(now);
  out.push_back(psnr(distortion));
  for (uint32_t id : order) {
    // Chains sum in a fixed order: the decoder's figure, bit for bit.
    if (id < estimates.chain.size() && estimates.chain[id] < now.size()) {
      now[estimates.chain[id]] = estimates.after[id];
    }
    distortion = estimates.Estimate(now);
    out.push_back(psnr(distortion));
  }
  return out;
}

Result<ParsedContainer> ParseContainer(std::string_view bytes,
                                       bool allow_truncated) {
  if (bytes.size() < 8) {
    return ParseError("container: " + std::to_string(bytes.size()) +
                      " bytes, shorter than the 8-byte preamble");
  }
  if (std::memcmp(bytes.data(), kContainerMagic, 4) != 0) {
    return ParseError("container: wrong magic (not a meshwave .mwv stream)");
  }
  const uint32_t header_length = GetU32(bytes.substr(4, 4));
  if (header_length > kMaxHeaderBytes) {
    return ParseError("container: header length " + std::to_string(header_length) +
                      " exceeds the limit");
  }
  if (header_length > bytes.size() - 8) {
    return Status(allow_truncated ? StatusCode::kNeedMoreInput
                                  : StatusCode::kParseError,
                  "container: header of " + std::to_string(header_length) +
                      " bytes but only " + std::to_string(bytes.size() - 8) +
                      " follow");
  }
  ParsedContainer out;
  auto header = ReadStreamHeader(bytes.substr(8, header_length));
  if (!header.ok()) return ParseError("container: the stream header does not parse");
  out.header = std::move(*header);
  if (out.header.format_version != kFormatVersion) {
    return Status(StatusCode::kUnsupported,
                  "container: format version " +
                      std::to_string(out.header.format_version) +
                      " (this build reads version " +
                      std::to_string(kFormatVersion) + ")");
  }
  const auto& index = out.header.packets;
  const size_t count = index.length.size();
  std::unordered_set<uint32_t> seen;
  std::string_view rest = bytes.substr(8 + header_length);
  for (uint32_t id : out.header.present) {
    if (id >= count) {
      return ParseError("container: packet id " + std::to_string(id) +
                        " is not in the index of " + std::to_string(count));
    }
    if (!seen.insert(id).second) {
      return ParseError("container: packet " + std::to_string(id) +
                        " is listed twice");
    }
    const uint32_t length = index.length[id];
    if (length > rest.size()) {
      if (!allow_truncated) {
        return ParseError("container: truncated inside packet " +
                          std::to_string(id) + " (" + std::to_string(length) +
                          " bytes expected, " + std::to_string(rest.size()) +
                          " left)");
      }
      out.missing_bytes += length - rest.size();
      rest = {};
      continue;
    }
    if (out.missing_bytes == 0) {
      out.ids.push_back(id);
      out.payloads.push_back(rest.substr(0, length));
      rest.remove_prefix(length);
    } else {
      out.missing_bytes += length;
    }
  }
  if (!rest.empty()) {
    return ParseError("container: " + std::to_string(rest.size()) +
                      " bytes after the last packet");
  }
  return out;
}

}  // namespace meshwave
