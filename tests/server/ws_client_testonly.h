// A small WebSocket client for the server tests: Beast over one loopback
// connection, protobuf messages of proto/websocket.proto, every read bounded
// by a timeout (async operations run on a private io_context for at most
// that long), pings counted.
#ifndef MESHWAVE_TESTS_SERVER_WS_CLIENT_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_WS_CLIENT_TESTONLY_H_

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "net.h"
#include "websocket.pb.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/beast/websocket.hpp>
#pragma GCC diagnostic pop

namespace meshwave::testing {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
namespace websocket = boost::beast::websocket;

class WsTestClient {
 public:
  using Clock = std::chrono::steady_clock;

  // Connects to 127.0.0.1:port and asks to upgrade on `target`.
  explicit WsTestClient(uint16_t port, const std::string& target = "/v1/ws")
      : ws_(ioc_) {
    beast::error_code ec;
    beast::get_lowest_layer(ws_).connect(
        {net::ip::make_address("127.0.0.1"), port}, ec);
    if (ec) return;
    ws_.control_callback(
        [this](websocket::frame_type kind, beast::string_view) {
          if (kind == websocket::frame_type::ping) ++pings_;
        });
    websocket::response_type response;
    ws_.handshake(response, "127.0.0.1", target, ec);
    status_ = response.result_int();
    open_ = !ec;
    ws_.binary(true);
  }

  bool open() const { return open_; }
  // The HTTP status of the upgrade answer: 101, or the refusal's.
  unsigned status() const { return status_; }
  int pings() const { return pings_; }
  // After a failed Read: why (closed by the server, timeout, ...).
  beast::error_code error() const { return error_; }
  websocket::close_reason close_reason() const { return ws_.reason(); }

  bool Send(const proto::ClientMessage& m) {
    return SendRaw(m.SerializeAsString());
  }
  bool SendRaw(const std::string& bytes, bool binary = true) {
    ws_.binary(binary);
    beast::error_code ec;
    ws_.write(net::buffer(bytes), ec);
    ws_.binary(true);
    return !ec;
  }

  // The next message; nullopt when the connection ends or nothing comes in
  // `timeout` (error() tells which; the socket is then closed).
  std::optional<proto::ServerMessage> Read(
      std::chrono::milliseconds timeout = std::chrono::seconds(20)) {
    StartRead();
    ioc_.restart();
    ioc_.run_for(timeout);
    if (read_pending_) {
      // Cancel the read by closing the socket, and let the handler run.
      beast::error_code ignored;
      beast::get_lowest_layer(ws_).socket().close(ignored);
      ioc_.restart();
      ioc_.run();
      error_ = beast::error::timeout;
      open_ = false;
      return std::nullopt;
    }
    return TakeMessage();
  }

  // Reads (answering pings) for `duration`; true when nothing arrived and
  // the connection is still open. The read stays pending for the next Read.
  bool IdleFor(std::chrono::milliseconds duration) {
    StartRead();
    ioc_.restart();
    ioc_.run_for(duration);
    if (!read_pending_) {
      TakeMessage();
      return false;
    }
    return true;
  }

  // Reads until a Done or an Error message (included) or a failure.
  std::vector<proto::ServerMessage> ReadUntilDone() {
    std::vector<proto::ServerMessage> out;
    while (auto m = Read()) {
      out.push_back(*m);
      if (m->has_done() || m->has_error()) break;
    }
    return out;
  }

  Clock::time_point last_arrival() const { return last_arrival_; }
  size_t last_size() const { return last_size_; }

  void Close() {
    beast::error_code ec;
    ws_.close(websocket::close_code::normal, ec);
    open_ = false;
  }

 private:
  void StartRead() {
    if (read_pending_) return;
    read_pending_ = true;
    buffer_.clear();
    ws_.async_read(buffer_, [this](beast::error_code ec, size_t) {
      error_ = ec;
      read_pending_ = false;
    });
  }

  std::optional<proto::ServerMessage> TakeMessage() {
    if (error_) {
      open_ = false;
      return std::nullopt;
    }
    last_arrival_ = Clock::now();
    proto::ServerMessage m;
    const auto data = buffer_.cdata();
    if (!m.ParseFromArray(data.data(), static_cast<int>(data.size()))) {
      error_ = net::error::invalid_argument;
      return std::nullopt;
    }
    last_size_ = data.size();
    return m;
  }

  net::io_context ioc_;
  websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
  bool open_ = false;
  bool read_pending_ = false;
  unsigned status_ = 0;
  int pings_ = 0;
  beast::error_code error_;
  Clock::time_point last_arrival_;
  size_t last_size_ = 0;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_WS_CLIENT_TESTONLY_H_
