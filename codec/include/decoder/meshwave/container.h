// The .mwv container: "MWV1" | u32 little-endian header length |
// StreamHeader (protobuf) | the payloads of the packets listed in the
// header's `present` field, in that order. Any subset of the packets that is
// closed under the packet dependencies makes a valid container.
#ifndef MESHWAVE_CONTAINER_H_
#define MESHWAVE_CONTAINER_H_

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// The preamble and header of the container holding the packets `ids`: a
// container's bytes up to the first payload (SerializeContainer in
// meshwave/encoder.h), so that a server can send the payloads from
// elsewhere (a memory map) after it, and a client can save what it holds.
std::string SerializeContainerHead(const StreamHeader& header,
                                   std::span<const uint32_t> ids);
// The same from the header's bytes without `present` (a server keeps them
// per mesh; StreamHeader::bytes_without_present).
std::string SerializeContainerHead(std::string_view header_without_present,
                                   std::span<const uint32_t> ids);

// Bytes the header's packed `present` field takes when its ids' varints
// take `id_bytes` bytes (0 when empty): for adding sizes up packet by packet.
uint64_t PresentFieldSize(uint64_t id_bytes);

// The size SerializeContainer would produce, without building it.
uint64_t ContainerSize(const StreamHeader& header,
                       std::span<const uint32_t> ids);

// Estimated PSNR (dB, peak = bounding-box diagonal) after each prefix of
// `order`: element i is the estimate once order[0 .. i) is decoded, the same
// figure ProgressiveDecoder::EstimatedPsnr gives (+infinity when no error
// is left). The header must have passed ValidateStreamHeader and `order`
// must hold ids of its index.
std::vector<double> EstimatedPsnrCurve(const StreamHeader& header,
                                       std::span<const uint32_t> order);

// The preamble: "MWV1" and the header length, 8 bytes.
inline constexpr size_t kContainerPreambleBytes = 8;

// The header length a container's preamble declares, the one reader of it
// (ParseContainer, the client's stream splitter). ParseError for fewer than
// 8 bytes or a wrong magic; the length is not checked against any limit
// (ParseContainer refuses one over kMaxHeaderBytes, meshwave/stream_limits.h).
Result<uint32_t> ReadContainerHeaderLength(std::string_view bytes);

struct ParsedContainer {
  StreamHeader header;
  std::vector<uint32_t> ids;               // packets whose payload is whole
  std::vector<std::string_view> payloads;  // views into the parsed bytes
  uint64_t missing_bytes = 0;  // > 0: the container was cut short
};

// Safe on untrusted bytes. Rejects a wrong magic, an unknown version, a
// header that does not parse, packet ids out of range or repeated, and
// trailing bytes. With allow_truncated, a container cut inside its payloads
// yields the complete packets before the cut (missing_bytes says how much
// is missing); otherwise that is an error too.
Result<ParsedContainer> ParseContainer(std::string_view bytes,
                                       bool allow_truncated = false);
// The payloads point into `bytes`: parsing a temporary string would leave
// them dangling (ASan found one such test), so that does not compile.
template <class S>
  requires std::same_as<S, std::string>
Result<ParsedContainer> ParseContainer(S&& bytes, bool allow_truncated = false) = delete;

}  // namespace meshwave

#endif  // MESHWAVE_CONTAINER_H_
