#include "meshwave/container.h"

#include <algorithm>
#include <cstring>
#include <unordered_set>

#include "core/protobuf_wire.h"
#include "stream/packet_index.h"
#include "stream/stream_format.h"

namespace meshwave {
namespace {

void PutU32(std::string& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

}  // namespace

uint64_t PresentFieldSize(uint64_t id_bytes) {
  return id_bytes == 0 ? 0 : 1 + VarintSize(id_bytes) + id_bytes;
}

uint64_t ContainerSize(const StreamHeader& header,
                       std::span<const uint32_t> ids) {
  // Sizes are added, not serialized: this runs once per packet when a
  // budget is fitted.
  uint64_t size = kContainerPreambleBytes + header.bytes_without_present.size();
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
  // `present` (packed varints) has the highest field number, so protobuf's
  // own serializer would write it last: appending it gives the same bytes as
  // serializing the header with the list set.
  std::string present;
  for (uint32_t id : ids) PutVarint(present, id);
  std::string field;
  if (!ids.empty()) {
    PutVarint(field, WireTag(kHeaderPresentField, kLengthDelimited));
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
  // ProgressiveDecoder::EstimatedPsnr, packet by packet.
  const double diagonal = HeaderDiagonal(header);
  auto psnr = [&](double distortion) {
    return EstimatedPsnrFromDistortion(header, diagonal, distortion);
  };
  std::vector<double> out;
  out.reserve(order.size() + 1);
  const DistortionEstimates estimates = ReadDistortionIndex(header, PacketChains(header));
  std::vector<double> now = estimates.chain_start;
  double distortion = estimates.Estimate(now);
  out.push_back(psnr(distortion));
  const PacketLayout layout(header);
  bool original_ready = false;  // the layer's coarse positions taken
  for (uint32_t id : order) {
    // Chains sum in a fixed order: the decoder's figure, bit for bit.
    if (id < estimates.chain.size() && estimates.chain[id] < now.size()) {
      now[estimates.chain[id]] = estimates.after[id];
    }
    original_ready = original_ready || layout.OriginalPart(id) == 1;
    distortion = estimates.ShownEstimate(now, original_ready);
    out.push_back(psnr(distortion));
  }
  return out;
}

Result<uint32_t> ReadContainerHeaderLength(std::string_view bytes) {
  if (bytes.size() < kContainerPreambleBytes) {
    return ParseError("container: " + std::to_string(bytes.size()) +
                      " bytes, shorter than the 8-byte preamble");
  }
  if (std::memcmp(bytes.data(), kContainerMagic, 4) != 0) {
    return ParseError("container: wrong magic (not a meshwave .mwv stream)");
  }
  uint32_t v = 0;  // little-endian
  for (int i = 7; i >= 4; --i) v = (v << 8) | static_cast<uint8_t>(bytes[static_cast<size_t>(i)]);
  return v;
}

Result<ParsedContainer> ParseContainer(std::string_view bytes,
                                       bool allow_truncated) {
  MW_ASSIGN_OR_RETURN(const uint32_t header_length, ReadContainerHeaderLength(bytes));
  if (header_length > kMaxHeaderBytes) {
    return ParseError("container: header length " + std::to_string(header_length) +
                      " exceeds the limit");
  }
  if (header_length > bytes.size() - kContainerPreambleBytes) {
    return Status(allow_truncated ? StatusCode::kNeedMoreInput
                                  : StatusCode::kParseError,
                  "container: header of " + std::to_string(header_length) +
                      " bytes but only " + std::to_string(bytes.size() - kContainerPreambleBytes) +
                      " follow");
  }
  ParsedContainer out;
  auto header = ReadStreamHeader(bytes.substr(kContainerPreambleBytes, header_length));
  if (!header.ok()) return ParseError("container: the stream header does not parse");
  out.header = std::move(*header);
  MW_RETURN_IF_ERROR(CheckFormatVersion(out.header).WithContext("container"));
  const auto& index = out.header.packets;
  const size_t count = index.length.size();
  std::unordered_set<uint32_t> seen;
  std::string_view rest = bytes.substr(kContainerPreambleBytes + header_length);
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
