#include "ws_server_messages.h"

#include "header_limit.h"
#include "websocket.pb.h"

namespace meshwave::client {
namespace {

StreamHead HeadOf(const proto::Selection& s) {
  StreamHead h;
  h.packets = s.next_cursor() >= s.from_cursor()
                  ? s.next_cursor() - s.from_cursor()
                  : 0;
  h.next_cursor = s.next_cursor();
  h.complete = s.next_cursor() == s.order_packets();
  h.content_length = s.bytes();
  return h;
}

Status StatusFromError(const proto::Error& e) {
  const std::string what = "the server refused: " + e.message();
  switch (e.code()) {
    case proto::Error::NOT_FOUND:
      return Status(StatusCode::kNotFound, what);
    case proto::Error::BAD_REQUEST:
      return InvalidArgument(what);
    case proto::Error::UNAVAILABLE:
      return IoError(what);  // worth retrying
    case proto::Error::CONFLICT:
      return Status(StatusCode::kStale, what);  // start over: the mesh was re-encoded
    default:
      return ParseError("an error message of unknown code " +
                        std::to_string(e.code()) + ": " + e.message());
  }
}

}  // namespace

ServerMessageReader::ServerMessageReader(bool expect_header,
                                         uint64_t max_header_bytes,
                                         StreamSink& sink, std::string where)
    : expect_header_(expect_header),
      max_header_bytes_(max_header_bytes),
      sink_(sink),
      where_(std::move(where)) {}

uint64_t ServerMessageReader::NextMessageLimit(uint64_t packet_limit) const {
  return expect_header_ && !selected_ ? HeaderMessageLimit(max_header_bytes_)
                                      : packet_limit;
}

Status ServerMessageReader::TooLarge(uint64_t packet_limit) const {
  if (expect_header_ && !selected_)
    return HeaderMessageTooLarge(max_header_bytes_);
  return ParseError(where_ + " sent a message over " +
                    std::to_string(packet_limit) + " bytes");
}

Result<std::optional<uint64_t>> ServerMessageReader::OnMessage(
    std::string_view bytes, bool binary) {
  using Done = std::optional<uint64_t>;
  proto::ServerMessage reply;
  if (!binary ||
      !reply.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return ParseError(where_ + " sent a message that does not parse");
  }
  switch (reply.message_case()) {
    case proto::ServerMessage::kStart:
      if (!expect_header_ || selected_) {
        return ParseError(where_ + " sent an unexpected stream header");
      }
      selected_ = true;
      container_ = reply.start().container();
      MW_RETURN_IF_ERROR(sink_.OnHead(HeadOf(reply.start().selection())));
      MW_RETURN_IF_ERROR(sink_.OnHeaderMessage(reply.start().header()));
      return Done();
    case proto::ServerMessage::kSelection:
      if (expect_header_ || selected_) {
        return ParseError(where_ + " sent an unexpected selection");
      }
      selected_ = true;
      MW_RETURN_IF_ERROR(sink_.OnHead(HeadOf(reply.selection())));
      return Done();
    case proto::ServerMessage::kPacket: {
      if (!selected_) {
        return ParseError(where_ + " sent a packet before its selection");
      }
      const auto& packet = reply.packet();
      MW_RETURN_IF_ERROR(sink_.OnUnitMessage(
          packet.cursor(),
          {packet.id(), packet.has_part() ? packet.part() : StreamUnit::kWholePacket},
          packet.payload()));
      return Done();
    }
    case proto::ServerMessage::kDone:
      if (!selected_) {
        return ParseError(where_ + " ended a stream it never started");
      }
      return Done(reply.done().next_cursor());
    case proto::ServerMessage::kError:
      return StatusFromError(reply.error());
    case proto::ServerMessage::MESSAGE_NOT_SET:
      break;
  }
  return ParseError(where_ + " sent an empty message");
}

}  // namespace meshwave::client
