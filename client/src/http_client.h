// HttpClient: one HTTP/1.1 connection to a server, plain or TLS, opened on
// demand and reopened after an error. GET only; bodies are handed over as
// they arrive. Not safe for concurrent requests: one at a time.
#ifndef MESHWAVE_CLIENT_HTTP_CLIENT_H_
#define MESHWAVE_CLIENT_HTTP_CLIENT_H_

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "meshwave/client/transport.h"
#include "meshwave/client/url.h"
#include "net.h"

namespace meshwave::client {

class HttpClient {
 public:
  using HeadHandler = std::function<Status(const http::response_header<>&)>;
  using BodyHandler = std::function<Status(std::string_view)>;

  HttpClient(net::any_io_executor executor, ServerUrl server,
             TransportOptions options);
  ~HttpClient();

  // GET `target`. A 200 response's head goes to on_head, its body to
  // on_body piece by piece; any other status becomes an error carrying the
  // server's message (kIoError for 5xx, kNotFound for 404, else
  // kInvalidArgument). Network failures and timeouts are kIoError; a
  // certificate that does not verify is kInvalidArgument.
  net::awaitable<Status> Get(std::string target, std::string accept,
                             HeadHandler on_head, BodyHandler on_body);
  // GET `target` whole; bodies over `limit` bytes are refused. `on_head`,
  // when given, sees a 200's head first.
  net::awaitable<Result<std::string>> GetBody(std::string target,
                                              std::string accept,
                                              uint64_t limit,
                                              HeadHandler on_head = {});
  void Close();
  net::any_io_executor executor() const { return executor_; }
  const ServerUrl& server() const { return server_; }

 private:
  bool connected() const { return plain_.has_value() || tls_.has_value(); }
  net::awaitable<Status> Connect();
  net::awaitable<Status> ExchangeOnce(const std::string& target,
                                      const std::string& accept,
                                      const HeadHandler& on_head,
                                      const BodyHandler& on_body,
                                      bool& got_head);
  template <class Stream>
  net::awaitable<Status> Exchange(Stream& stream, const std::string& target,
                                  const std::string& accept,
                                  const HeadHandler& on_head,
                                  const BodyHandler& on_body, bool& got_head);

  net::any_io_executor executor_;
  ServerUrl server_;
  TransportOptions options_;
  std::unique_ptr<ssl::context> ssl_context_;
  std::optional<beast::tcp_stream> plain_;
  std::optional<beast::ssl_stream<beast::tcp_stream>> tls_;
  beast::flat_buffer buffer_;
  bool keep_alive_ = false;
};

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_HTTP_CLIENT_H_
