// A split packet's payload (docs/FORMAT.md 2.2): one codeword per precinct
// of its subband, behind the lengths of all but the last as varints
// (LEB128, as protobuf writes them). The last part's length is what
// remains, so a subband of one precinct splits into exactly the codeword
// an unsplit packet holds.
#ifndef MESHWAVE_STREAM_PACKET_PARTS_H_
#define MESHWAVE_STREAM_PACKET_PARTS_H_

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

std::string JoinPacketParts(std::span<const std::string> parts);

// The `count` parts of a split payload, as views into it. ParseError when
// the table is truncated or its lengths overrun the payload.
Result<std::vector<std::string_view>> SplitPacketParts(std::string_view payload,
                                                       uint32_t count);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_PACKET_PARTS_H_
