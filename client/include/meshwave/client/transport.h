// Transport: how a Session asks a server for a stream's header and packets.
// HTTP (/header, /packets/{k}, /stream?from=) is the one built here; a
// WebSocket transport (/v1/ws) can implement the same interface.
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
#include "meshwave/status.h"

namespace meshwave::client {

namespace net = boost::asio;

struct TransportOptions {
  std::chrono::milliseconds connect_timeout{
      5000};  // resolve, connect, TLS handshake
  std::chrono::milliseconds read_timeout{10000};  // each write and each read
  // PEM file of certificates to trust for https instead of the system's.
  std::string ca_file;
};

// A prefix of a packet order from a cursor: GET
// /stream?order=&max_level=&from=&budget=.
struct StreamRequest {
  Progression order = Progression::kQuality;
  int max_level = -1;              // -1: all levels
  size_t from = 0;                 // 0: the body is a container, header first
  std::optional<uint64_t> budget;  // bytes as the server counts them
};

// What the server says about a stream response before its body.
struct StreamHead {
  size_t packets = 0;
  size_t next_cursor = 0;
  bool complete = false;
  std::optional<uint64_t> content_length;
};

// Receives a response body piece by piece; an error stops the transfer and
// is returned by the transport unchanged.
class StreamSink {
 public:
  virtual ~StreamSink() = default;
  virtual Status OnHead(const StreamHead& head) = 0;
  virtual Status OnBytes(std::string_view bytes) = 0;
};

// Errors: kIoError for failures worth retrying (refused, reset or dropped
// connection, timeout, 5xx); any other code is final (4xx, a malformed
// response, a TLS certificate that does not verify).
class Transport {
 public:
  virtual ~Transport() = default;
  virtual net::any_io_executor executor() = 0;
  // The StreamHeader of the mesh, protobuf bytes (present empty).
  virtual net::awaitable<Result<std::string>> GetHeader() = 0;
  // The payload of packet `id` of the index.
  virtual net::awaitable<Result<std::string>> GetPacket(uint32_t id) = 0;
  virtual net::awaitable<Status> Stream(const StreamRequest& request,
                                        StreamSink& sink) = 0;
  // Closes the connection; a later request opens a new one.
  virtual void Close() = 0;
};

// HTTP/1.1 (http:// or https:// with certificate and host name
// verification) to the mesh at `url`, one keep-alive connection at a time.
std::unique_ptr<Transport> MakeHttpTransport(net::any_io_executor executor,
                                             const MeshUrl& url,
                                             const TransportOptions& options);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_TRANSPORT_H_
