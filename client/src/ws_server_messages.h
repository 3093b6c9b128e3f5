// ServerMessageReader: the WebSocket transport's parser of what the server
// sends (proto/websocket.proto ServerMessage; docs/API.md, WebSocket), one
// request's answer message by message. Untrusted bytes: every message is
// checked against the request (a header only after a start, packets only
// after their selection, Done only after one) and handed to the StreamSink;
// anything else is a kParseError naming `where`.
#ifndef MESHWAVE_CLIENT_WS_SERVER_MESSAGES_H_
#define MESHWAVE_CLIENT_WS_SERVER_MESSAGES_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/client/transport.h"
#include "meshwave/status.h"

namespace meshwave::client {

class ServerMessageReader {
 public:
  // `expect_header`: the request was a start, so the answer begins with the
  // header. `max_header_bytes`: the client's limit on it (header_limit.h).
  ServerMessageReader(bool expect_header, uint64_t max_header_bytes,
                      StreamSink& sink, std::string where);

  // The largest message to accept next, for the transport to enforce on the
  // frame's declared length before reading it: HeaderMessageLimit until the
  // header has come, `packet_limit` after.
  uint64_t NextMessageLimit(uint64_t packet_limit) const;
  // The error for a message refused by that limit.
  Status TooLarge(uint64_t packet_limit) const;

  // One message; `binary`: it came in binary frames. nullopt: read on; a
  // value: the stream is done and the server stopped at that cursor.
  Result<std::optional<uint64_t>> OnMessage(std::string_view bytes,
                                            bool binary);

  // The container a StreamStart named (StreamStart.container), empty
  // before one or from a server that does not say.
  const std::string& container() const { return container_; }

 private:
  bool expect_header_;
  uint64_t max_header_bytes_;
  StreamSink& sink_;
  std::string where_;
  bool selected_ = false;
  std::string container_;
};

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_WS_SERVER_MESSAGES_H_
