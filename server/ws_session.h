// One WebSocket connection on GET /v1/ws (docs/API.md, WebSocket): the
// socket's role. Reads client messages (ParseClientMessage), hands their
// requests to its StreamCursor, which selects the units, and sends them as
// binary messages, paced by a token bucket on a steady_timer; pings a
// silent client. One write in flight at a time and a short queue of small
// messages; when the queue is full the session stops reading, so nothing
// grows without bound. Lives by shared_from_this on the strand of the
// connection it was upgraded from.
#ifndef MESHWAVE_SERVER_WS_SESSION_H_
#define MESHWAVE_SERVER_WS_SESSION_H_

#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "meshwave/client_message.h"
#include "net.h"
#include "server_context.h"
#include "stream_cursor.h"
#include "token_bucket.h"
#include "ws_protocol.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/beast/websocket.hpp>
#pragma GCC diagnostic pop

namespace meshwave::server {

namespace websocket = boost::beast::websocket;

class WsSession : public Closable,
                  public std::enable_shared_from_this<WsSession> {
 public:
  WsSession(tcp::socket&& socket, ServerContext& ctx);
  ~WsSession() override;

  // Answers the upgrade request (101) and starts reading.
  void Run(const http::request<http::string_body>& upgrade);
  // Ends the session with close code 1001 after the write in flight.
  void Shutdown() override;

 private:
  struct Outgoing {
    std::string bytes;  // a serialized ServerMessage
    bool paced;         // counts against the rate (the header does)
  };

  void OnAccept(beast::error_code ec);
  void DoRead();
  void OnRead(beast::error_code ec, size_t bytes);
  void Handle(const ClientRequest& request);
  void StartStream(const ClientRequest& request);
  void RefineStream(const ClientRequest& request);
  void SetPacing(uint64_t rate);
  void SendError(proto::Error::Code code, const std::string& message);
  // The cursor's refusal: BAD_REQUEST for the client's mistakes, else
  // UNAVAILABLE (the mesh's units cannot be built).
  void SendError(const Status& status);
  void Queue(const proto::ServerMessage& message, bool paced);
  bool streaming() const { return stream_.pending() > 0; }

  // Keep-alive: pings a client silent for websocket_ping_seconds and closes
  // one silent for twice that with a close frame (1008), then drops the
  // socket if even the close gets no answer.
  void ArmKeepAlive();
  void OnKeepAlive(beast::error_code ec);
  void StopTimers();

  // Writes the next message if there is one and the rate allows it.
  void Pump();
  // True when `bytes` may go now; otherwise arms the pacing timer.
  bool MayWriteNow(uint64_t bytes);
  void OnPacingTimer(beast::error_code ec);
  void OnWrite(beast::error_code ec, size_t bytes);
  void DoClose(websocket::close_reason reason);
  void Fail(beast::error_code ec, const char* what);

  websocket::stream<beast::tcp_stream> ws_;
  ServerContext& ctx_;
  net::steady_timer pacing_timer_;
  net::steady_timer keepalive_timer_;
  std::chrono::steady_clock::time_point last_heard_;  // a frame from the client
  std::chrono::steady_clock::time_point last_ping_;   // sent by us
  bool ping_in_flight_ = false;
  beast::flat_buffer read_buffer_;
  std::deque<Outgoing> queue_;
  // The message being written: a queued one, or a packet's prefix with its
  // payload read from the mesh's memory map (kept alive by in_flight_mesh_).
  std::string in_flight_;
  std::shared_ptr<const ServedMesh> in_flight_mesh_;
  bool writing_ = false;
  bool timer_armed_ = false;
  bool reading_ = false;
  bool closing_ = false;            // no more reads or writes
  bool close_after_write_ = false;  // Shutdown during a write

  // What the client's requests selected and what is left to send.
  StreamCursor stream_;
  std::optional<TokenBucket> pacer_;

  std::string remote_;
  std::chrono::steady_clock::time_point opened_;
  uint64_t bytes_sent_ = 0;
  uint64_t packets_sent_ = 0;
  uint64_t requests_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_WS_SESSION_H_
