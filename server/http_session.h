// One HTTP/1.1 connection: reads requests one at a time (a fresh parser
// each, with header and body limits and an idle timeout), answers them and
// keeps the connection alive while the client wants. Lives by
// shared_from_this on its own strand.
#ifndef MESHWAVE_SERVER_HTTP_SESSION_H_
#define MESHWAVE_SERVER_HTTP_SESSION_H_

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "net.h"
#include "server_context.h"
#include "slices_body.h"

namespace meshwave::server {

class HttpSession : public Closable, public std::enable_shared_from_this<HttpSession> {
 public:
  // `over_capacity`: answer the first request with 503 and close.
  HttpSession(tcp::socket&& socket, ServerContext& ctx, bool over_capacity);
  ~HttpSession() override;

  void Run();
  void Shutdown() override;

 private:
  void DoRead();
  void OnFirstBytes(beast::error_code ec, size_t bytes);
  void DoReadHeader();
  void OnHeader(beast::error_code ec, size_t bytes);
  void OnContinueSent(beast::error_code ec, size_t bytes);
  void DoReadBody();
  void OnBody(beast::error_code ec, size_t bytes);
  // Sends `response`; `close` ends the connection after it whatever the
  // client asked (the request body was not read, or the server stops).
  void DoWrite(Response response, bool close);
  void OnWrite(bool close, beast::error_code ec, size_t bytes);
  void DoClose();
  void DoDrain();
  void Fail(beast::error_code ec, const char* what);
  Response ParseFailure(beast::error_code ec);

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  ServerContext& ctx_;
  const bool over_capacity_;
  std::string client_;  // the peer's address, for per-client rate limits
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<Response> response_;  // the one being written
  std::shared_ptr<http::response<http::empty_body>> continue_;
  std::chrono::steady_clock::time_point started_;
  unsigned version_ = 11;
  bool head_ = false;
  bool waiting_for_request_ = false;  // idle between requests
  bool shutting_down_ = false;
  static constexpr size_t kMaxDrainBytes = 4u << 20;
  std::array<char, 16384> drain_;
  size_t drained_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_HTTP_SESSION_H_
