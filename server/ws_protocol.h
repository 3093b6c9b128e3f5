// The wire protocol of GET /v1/ws (proto/websocket.proto): client messages
// parsed and checked into a ClientRequest without any socket (a fuzz target
// calls ParseClientMessage directly), and server messages serialized,
// packets without copying their payload.
#ifndef MESHWAVE_SERVER_WS_PROTOCOL_H_
#define MESHWAVE_SERVER_WS_PROTOCOL_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/status.h"
#include "websocket.pb.h"

namespace meshwave::server {

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
  // kStart and kResume.
  std::string mesh_id;
  Progression order = Progression::kQuality;
  int max_level = -1;              // -1: all levels
  std::optional<uint64_t> budget;  // absent: the whole order
  uint64_t rate = 0;               // bytes/s, 0: unpaced
  bool header_only = false;        // kStart
  uint32_t cursor = 0;             // kResume
  uint64_t extra_bytes = 0;        // kRefine, >= 1
  // Region requests (docs/API.md): a region or view to refine first (all
  // three kinds; start and resume leave `order` at its default with one).
  std::optional<Region> region;
  bool refine_order = false;       // kRefine: `order` names a new order
  // kResume of a session counting units: the held bitmap's text (checked
  // against the mesh by the session); set, maybe empty, with a region too.
  std::optional<std::string> held;
  bool units() const { return region.has_value() || held.has_value(); }
};

// Parses one binary message from a client. Safe on any bytes: kInvalidArgument
// with a message for the client when the message is larger than the limit,
// does not parse, holds no request, names a malformed mesh id or an unknown
// order, or has a number out of range (max_level > kMaxLevelLimit, budgets
// and extra_bytes > kMaxBudget, rate > kMaxRate or in (0, kMinRate), extra_bytes 0,
// header_only
// with a budget); a region or view that does not parse, both at once, a
// screen error without a view, a region beside an order, and a resume with
// both a cursor and held units. Limits that depend on the mesh (levels,
// order length, the held bitmap) are the session's to check.
Result<ClientRequest> ParseClientMessage(std::string_view bytes,
                                         const WsLimits& limits);

// A serialized ServerMessage holding `error`.
std::string ErrorMessage(proto::Error::Code code, std::string_view message);

// The bytes of a ServerMessage holding Packet{cursor, id, part, payload}
// that come before the payload: the frame is this prefix followed by the
// payload itself, byte for byte what SerializeAsString would give without
// a part (with one, `part` comes before the payload).
std::string PacketMessagePrefix(uint32_t cursor, uint32_t id, uint64_t payload_size,
                                std::optional<uint32_t> part = std::nullopt);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_WS_PROTOCOL_H_
