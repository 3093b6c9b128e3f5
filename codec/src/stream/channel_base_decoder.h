// A channel's base values (docs/FORMAT.md 2.3): its values at the base
// vertices, three components each, quantised on the channel's base step
// and stored in the header as zigzag varints.
#ifndef MESHWAVE_STREAM_CHANNEL_BASE_DECODER_H_
#define MESHWAVE_STREAM_CHANNEL_BASE_DECODER_H_

#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

// The base values of `channel` for `base_vertices` vertices: base_step
// times the integers of `channel.base`. Safe on untrusted bytes: ParseError
// when the field does not hold exactly 3 * base_vertices varints of at most
// 5 bytes, each of a 32-bit signed value, or when base_step is not finite
// and positive.
Result<std::vector<Vec3>> DecodeChannelBase(const StreamHeader::Channel& channel,
                                            uint32_t base_vertices);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_CHANNEL_BASE_DECODER_H_
