// The server's messages of GET /v1/ws (proto/websocket.proto): serialized,
// packets without copying their payload. The client's messages are parsed
// in the protocol layer (meshwave/client_message.h).
#ifndef MESHWAVE_SERVER_WS_PROTOCOL_H_
#define MESHWAVE_SERVER_WS_PROTOCOL_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "websocket.pb.h"

namespace meshwave::server {

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
