// The client messages of GET /v1/ws (proto/websocket.proto, docs/API.md):
// parsed and checked into a ClientRequest without any socket (a fuzz target
// calls ParseClientMessage directly). A start's and a resume's stream
// fields are checked by CheckStreamRequest (meshwave/stream_request.h), as
// GET /stream's query is.
#ifndef MESHWAVE_CLIENT_MESSAGE_H_
#define MESHWAVE_CLIENT_MESSAGE_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "meshwave/status.h"
#include "meshwave/stream_request.h"

namespace meshwave {

// Pacing above this is refused: 2^40 bytes/s is no pacing at all, and the
// bound keeps the token arithmetic far from overflow.
inline constexpr uint64_t kMaxRate = uint64_t{1} << 40;
// Pacing below this is refused (0, unpaced, is not pacing): at 1 B/s one
// packet of a few kB would hold a session, its memory map and a slot of
// max_websocket_sessions for hours. 1024 B/s sends the largest sample
// container (about 80 kB) in under 2 minutes.
inline constexpr uint64_t kMinRate = 1024;

struct WsLimits {
  size_t max_message_bytes = 64 * 1024;
};

struct ClientRequest {
  enum class Kind { kStart, kRefine, kResume };
  Kind kind = Kind::kStart;
  // kStart and kResume: the mesh and its stream (`from`: a resume's
  // cursor; `held`: a resume's held units, when not empty). kRefine:
  // `order` or `region` when it names one.
  std::string mesh_id;
  StreamRequest stream;
  uint64_t rate = 0;          // bytes/s, 0: unpaced
  bool header_only = false;   // kStart
  uint64_t extra_bytes = 0;   // kRefine, >= 1
  bool refine_order = false;  // kRefine: `stream.order` names a new order
};

// Parses one binary message from a client. Safe on any bytes:
// kInvalidArgument with a message for the client when the message is larger
// than the limit, does not parse, holds no request, names a malformed mesh
// id, has a rate above kMaxRate or in (0, kMinRate), extra_bytes 0 or above
// kMaxBudget, header_only with a budget, or stream fields CheckStreamRequest
// refuses.
Result<ClientRequest> ParseClientMessage(std::string_view bytes, const WsLimits& limits);

}  // namespace meshwave

#endif  // MESHWAVE_CLIENT_MESSAGE_H_
