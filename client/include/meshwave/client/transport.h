// Transport: how a Session asks a server for a stream's header and packets.
// Two are built here: HTTP (/header, /packets/{k}, /stream?from=) and
// WebSocket (/v1/ws: start, refine on the same socket, resume after a
// reconnect).
#ifndef MESHWAVE_CLIENT_TRANSPORT_H_
#define MESHWAVE_CLIENT_TRANSPORT_H_

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/awaitable.hpp>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/client/url.h"
#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/held_units.h"
#include "meshwave/status.h"
#include "meshwave/stream_limits.h"

namespace meshwave::client {

namespace net = boost::asio;

// The default limit on a stream header (SessionOptions::max_header_bytes):
// the format's own limit (meshwave/stream_limits.h).
inline constexpr uint64_t kDefaultMaxHeaderBytes = kMaxHeaderBytes;

struct TransportOptions {
  std::chrono::milliseconds connect_timeout{
      5000};  // resolve, connect, TLS handshake
  std::chrono::milliseconds read_timeout{10000};  // each write and each read
  // PEM file of certificates to trust for https instead of the system's.
  std::string ca_file;
  // WebSocket only: the rate the server paces the stream to, bytes per
  // second (0: as fast as the connection takes it).
  uint64_t pace_bytes_per_second = 0;
};

// A prefix of a packet order from a cursor: GET
// /stream?order=&max_level=&from=&budget=.
struct StreamRequest {
  Progression order = Progression::kQuality;
  int max_level = -1;              // -1: all levels
  size_t from = 0;                 // 0: the body is a container, header first
  std::optional<uint64_t> budget;  // bytes as the server counts them
  // The caller holds the header: payloads only, from cursor 0 too (budget
  // in payload bytes). Only for transports with CanStreamPayloadsFromStart.
  bool header_held = false;
  // A header longer than this is refused before it is buffered.
  uint64_t max_header_bytes = kDefaultMaxHeaderBytes;
};

// What the server says about a stream response before its body.
struct StreamHead {
  size_t packets = 0;
  size_t next_cursor = 0;
  bool complete = false;
  std::optional<uint64_t> content_length;
};

// Receives a response body piece by piece; an error stops the transfer and
// is returned by the transport unchanged. A byte transport (HTTP) calls
// OnHead, then OnBytes; a message transport (WebSocket) calls OnHead, then
// OnHeaderMessage (from cursor 0 without the header held) and OnPacketMessage
// per packet.
class StreamSink {
 public:
  virtual ~StreamSink() = default;
  virtual Status OnHead(const StreamHead& head) = 0;
  virtual Status OnBytes(std::string_view bytes) = 0;
  // The StreamHeader, protobuf bytes with `present` empty.
  virtual Status OnHeaderMessage(std::string_view header) = 0;
  // The packet at `cursor` of the order, `id` in the header's index.
  virtual Status OnPacketMessage(size_t cursor, uint32_t id,
                                 std::string_view payload) = 0;
  // A Packet message that may carry a part of a split packet (a session
  // counting units); a stream of packets refuses parts.
  virtual Status OnUnitMessage(size_t cursor, StreamUnit unit, std::string_view payload) {
    if (!unit.whole()) return ParseError("a part of a split packet in a stream of packets");
    return OnPacketMessage(cursor, unit.id, payload);
  }
};

// The units of a region request (docs/API.md, "Region requests"), from
// what the client holds: GET /stream?region|view=&held=&budget= over HTTP,
// a `resume` with `held` over WebSocket. Each request names everything
// held, so none depends on an earlier one.
struct UnitStreamRequest {
  std::optional<Region> region;  // absent: the uniform `order`
  Progression order = Progression::kQuality;
  int max_level = -1;              // -1: all levels
  std::string held;                // the held bitmap's text (stream_units.h)
  std::optional<uint64_t> budget;  // payload bytes; absent: everything
  uint64_t max_payload = uint64_t{1} << 30;  // a longer unit is refused
};

class UnitSink {
 public:
  virtual ~UnitSink() = default;
  virtual Status OnUnit(StreamUnit unit, std::string_view payload) = 0;
};

// Errors: kIoError for failures worth retrying (refused, reset or dropped
// connection, timeout, 5xx); any other code is final (4xx, a malformed
// response, a TLS certificate that does not verify).
class Transport {
 public:
  virtual ~Transport() = default;
  virtual net::any_io_executor executor() = 0;
  // The StreamHeader of the mesh, protobuf bytes (present empty); one over
  // `max_header_bytes` is refused before it is buffered.
  virtual net::awaitable<Result<std::string>> GetHeader(
      uint64_t max_header_bytes) = 0;
  // The payload of packet `id` of the index.
  virtual net::awaitable<Result<std::string>> GetPacket(uint32_t id) = 0;
  virtual net::awaitable<Status> Stream(const StreamRequest& request,
                                        StreamSink& sink) = 0;
  // Closes the connection; a later request opens a new one.
  virtual void Close() = 0;
  // Whether Stream takes StreamRequest::header_held (WebSocket); otherwise
  // the Session fetches the first packet by id (HTTP: /stream from cursor 0
  // always starts with the header).
  virtual bool CanStreamPayloadsFromStart() const { return false; }
  // Units of a region request, each handed to `sink` as it arrives.
  virtual net::awaitable<Status> StreamUnits(const UnitStreamRequest& request, UnitSink& sink) {
    (void)request;
    (void)sink;
    co_return Status(StatusCode::kUnsupported, "this transport has no region requests");
  }
};

// HTTP/1.1 (http:// or https:// with certificate and host name
// verification) to the mesh at `url`, one keep-alive connection at a time.
std::unique_ptr<Transport> MakeHttpTransport(net::any_io_executor executor,
                                             const MeshUrl& url,
                                             const TransportOptions& options);

// WebSocket (ws:// or wss://, TLS verified as for https) to GET /v1/ws of
// the server at `url`. One connection, kept open between requests: a
// request that continues where the server's stream stopped is a `refine`
// on the same socket; after a reconnect it is a `resume` from the cursor.
// Streams are paced to options.pace_bytes_per_second.
std::unique_ptr<Transport> MakeWebSocketTransport(
    net::any_io_executor executor, const MeshUrl& url,
    const TransportOptions& options);

// The transport the URL's scheme names: WebSocket for ws:// and wss://,
// HTTP otherwise.
std::unique_ptr<Transport> MakeTransport(net::any_io_executor executor,
                                         const MeshUrl& url,
                                         const TransportOptions& options);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_TRANSPORT_H_
