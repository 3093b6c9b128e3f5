// One HTTP/1.1 connection: reads requests one at a time (a fresh parser
// each, with header and body limits and an idle timeout), answers them and
// keeps the connection alive while the client wants. Each response goes out
// in one gathered write of its head (serialised here, or cached) and body
// slices; repeated GETs of the mesh endpoints come from the ResponseCache.
// Every timeout is a LazyDeadline on one timer. Lives by shared_from_this
// on its socket's executor (one io thread's io_context, or a strand).
#ifndef MESHWAVE_SERVER_HTTP_SESSION_H_
#define MESHWAVE_SERVER_HTTP_SESSION_H_

#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lazy_deadline.h"
#include "net.h"
#include "response_cache.h"
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
  void ParseHeader();
  void OnHeader(beast::error_code ec, size_t bytes);
  void OnContinueSent(beast::error_code ec, size_t bytes);
  void DoReadBody();
  void OnBody(beast::error_code ec, size_t bytes);
  // A complete request: from the response cache, else HandleRequest.
  void Answer();
  bool AnswerFromCache();
  // Sends `response`; `close` ends the connection after it whatever the
  // client asked (the request body was not read, or the server stops).
  void DoWrite(Response response, bool close);
  void WriteCached(std::shared_ptr<const CachedResponse> cached,
                   std::shared_ptr<const ServedMesh> mesh, bool close);
  bool KeepAlive(bool close) const;
  // buffers_ += head_bytes_ ended by the Connection field; += the body
  // unless the request is a HEAD.
  void QueueHead(bool keep_alive);
  void QueueBody(const std::string& owned, const std::vector<net::const_buffer>& slices);
  void StartWrite(bool keep_alive);
  void OnWrite(bool close, beast::error_code ec, size_t bytes);
  void DoClose();
  void DoDrain();
  void OnDeadline();
  void Fail(beast::error_code ec, const char* what);
  Response ParseFailure(beast::error_code ec);

  // A view of buffers_ for async_write: copying it copies two pointers,
  // where a std::vector would be copied into the operation.
  struct BufferView {
    using value_type = net::const_buffer;
    using const_iterator = const net::const_buffer*;
    const net::const_buffer* first;
    const net::const_buffer* last;
    const_iterator begin() const { return first; }
    const_iterator end() const { return last; }
  };

  tcp::socket socket_;
  LazyDeadline deadline_;
  beast::flat_buffer buffer_;
  ServerContext& ctx_;
  const bool over_capacity_;
  std::string client_;  // the peer's address, for per-client rate limits
  std::optional<http::request_parser<http::string_body>> parser_;
  std::shared_ptr<http::response<http::empty_body>> continue_;
  std::chrono::steady_clock::time_point started_;
  unsigned version_ = 11;
  bool head_ = false;
  bool upload_ = false;  // the request being read is an upload
  bool waiting_for_request_ = false;  // idle between requests
  bool shutting_down_ = false;
  // The response being written: its head (for responses not from the
  // cache, and cached ones other than HTTP/1.1 keep-alive), the message or
  // cache entry that owns the body, and the buffers of the gathered write.
  std::string head_bytes_;
  std::optional<Response> response_;
  std::shared_ptr<const CachedResponse> cached_;
  std::shared_ptr<const ServedMesh> mesh_;
  std::vector<net::const_buffer> buffers_;
  unsigned status_ = 0;
  // The request's key in the response cache; empty: not cacheable.
  std::string cache_key_;
  bool cacheable_ = false;
  static constexpr size_t kMaxDrainBytes = 4u << 20;
  std::array<char, 16384> drain_;
  size_t drained_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_HTTP_SESSION_H_
