// The client's limit on a stream header (SessionOptions::max_header_bytes,
// `meshwave fetch --max-header`), checked in this one place wherever a
// header's size is first known and before its bytes are buffered:
//   - HTTP /stream: the container's length field (StreamSplitter);
//   - HTTP GET /header (the --psnr path): Content-Length, else the bytes as
//     they arrive;
//   - WebSocket: the size a frame declares for the message that carries the
//     header (a start, or the header_only start of the --psnr path), through
//     Beast's read_message_max, checked before the payload is read.
#ifndef MESHWAVE_CLIENT_HEADER_LIMIT_H_
#define MESHWAVE_CLIENT_HEADER_LIMIT_H_

#include <cstdint>

#include "meshwave/status.h"

namespace meshwave::client {

// kParseError (final, not retried) when `header_bytes` is over `limit`.
Status CheckHeaderLength(uint64_t header_bytes, uint64_t limit);

// The largest WebSocket message that may carry a header of `limit` bytes:
// the header, the selection beside it and their protobuf framing.
uint64_t HeaderMessageLimit(uint64_t limit);

// The error for a header message over HeaderMessageLimit(limit), refused
// from its frame's declared length before it was read.
Status HeaderMessageTooLarge(uint64_t limit);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_HEADER_LIMIT_H_
