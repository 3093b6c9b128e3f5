#include "ws_protocol.h"

#include "core/protobuf_wire.h"

namespace meshwave::server {

std::string ErrorMessage(proto::Error::Code code, std::string_view message) {
  proto::ServerMessage m;
  m.mutable_error()->set_code(code);
  m.mutable_error()->set_message(std::string(message));
  return m.SerializeAsString();
}

std::string PacketMessagePrefix(uint32_t cursor, uint32_t id,
                                uint64_t payload_size, std::optional<uint32_t> part) {
  // Wire format, fields in number order as protobuf writes them but `part`
  // (4) before the payload (3), which must come last; proto3 leaves zero
  // numbers and empty bytes out, an optional field is written when set.
  // Every tag is one byte (field numbers below 16).
  constexpr uint32_t kPacketTag =
      WireTag(proto::ServerMessage::kPacketFieldNumber, kLengthDelimited);
  constexpr uint32_t kCursorTag = WireTag(proto::Packet::kCursorFieldNumber, kVarint);
  constexpr uint32_t kIdTag = WireTag(proto::Packet::kIdFieldNumber, kVarint);
  constexpr uint32_t kPayloadTag = WireTag(proto::Packet::kPayloadFieldNumber, kLengthDelimited);
  constexpr uint32_t kPartTag = WireTag(proto::Packet::kPartFieldNumber, kVarint);
  static_assert(kPacketTag < 0x80 && kCursorTag < 0x80 && kIdTag < 0x80 && kPayloadTag < 0x80 &&
                kPartTag < 0x80);
  uint64_t inner = 0;
  if (cursor != 0) inner += 1 + VarintSize(cursor);
  if (id != 0) inner += 1 + VarintSize(id);
  if (part) inner += 1 + VarintSize(*part);
  if (payload_size != 0) inner += 1 + VarintSize(payload_size) + payload_size;
  std::string out;
  out.reserve(24);
  PutVarint(out, kPacketTag);
  PutVarint(out, inner);
  if (cursor != 0) {
    PutVarint(out, kCursorTag);
    PutVarint(out, cursor);
  }
  if (id != 0) {
    PutVarint(out, kIdTag);
    PutVarint(out, id);
  }
  if (part) {
    PutVarint(out, kPartTag);
    PutVarint(out, *part);
  }
  if (payload_size != 0) {
    PutVarint(out, kPayloadTag);
    PutVarint(out, payload_size);
  }
  return out;
}

}  // namespace meshwave::server
