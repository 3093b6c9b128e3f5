#include "http_client.h"

#include <vector>

#include "co_status.h"
#include "server_connection.h"

namespace meshwave::client {
namespace {

constexpr size_t kChunkBytes = 64 * 1024;
constexpr size_t kErrorBodyLimit = 64 * 1024;

}  // namespace

HttpClient::HttpClient(net::any_io_executor executor, ServerUrl server,
                       TransportOptions options)
    : executor_(std::move(executor)),
      server_(std::move(server)),
      options_(std::move(options)) {}

HttpClient::~HttpClient() = default;

void HttpClient::Close() {
  plain_.reset();
  tls_.reset();
  buffer_.clear();
  keep_alive_ = false;
}

net::awaitable<Status> HttpClient::Connect() {
  Close();
  if (!server_.tls) {
    plain_.emplace(executor_);
    Status s = co_await ConnectTcp(*plain_, server_, options_);
    if (!s.ok()) Close();
    co_return s;
  }
  if (!ssl_context_) {
    auto ctx = MakeTlsContext(options_);
    if (!ctx.ok()) co_return ctx.status();
    ssl_context_ = std::move(*ctx);
  }
  tls_.emplace(executor_, *ssl_context_);
  Status s = co_await ConnectTls(*tls_, server_, options_);
  if (!s.ok()) Close();
  co_return s;
}

template <class Stream>
net::awaitable<Status> HttpClient::Exchange(
    Stream& stream, const std::string& target, const std::string& accept,
    const HeadHandler& on_head, const BodyHandler& on_body, bool& got_head) {
  auto& lowest = beast::get_lowest_layer(stream);
  http::request<http::empty_body> req{http::verb::get, target, 11};
  req.set(http::field::host, HostHeader(server_));
  req.set(http::field::user_agent, "meshwave-client/0.1");
  if (!accept.empty()) req.set(http::field::accept, accept);
  lowest.expires_after(options_.read_timeout);
  auto [wec, wn] = co_await http::async_write(stream, req, Tuple());
  if (wec)
    co_return NetError("sending GET " + target, wec, options_.read_timeout);

  http::response_parser<http::buffer_body> parser;
  parser.body_limit(
      boost::none);  // callers check lengths against what they expect
  lowest.expires_after(options_.read_timeout);
  auto [hec, hn] =
      co_await http::async_read_header(stream, buffer_, parser, Tuple());
  if (hec)
    co_return NetError("reading the response to GET " + target, hec,
                       options_.read_timeout);
  got_head = true;
  keep_alive_ = parser.keep_alive();
  const unsigned code = parser.get().result_int();

  std::string error_body;
  if (code == 200) {
    Status s = on_head(parser.get().base());
    if (!s.ok()) {
      keep_alive_ = false;
      co_return s;
    }
  }
  std::vector<char> chunk(kChunkBytes);
  while (!parser.is_done()) {
    parser.get().body().data = chunk.data();
    parser.get().body().size = chunk.size();
    lowest.expires_after(options_.read_timeout);
    auto [rec, rn] =
        co_await http::async_read_some(stream, buffer_, parser, Tuple());
    if (rec == http::error::need_buffer) rec = {};
    if (rec) {
      keep_alive_ = false;
      co_return NetError("reading the body of GET " + target, rec,
                         options_.read_timeout);
    }
    const size_t got = chunk.size() - parser.get().body().size;
    if (got == 0) continue;
    if (code != 200) {
      if (error_body.size() < kErrorBodyLimit)
        error_body.append(chunk.data(), got);
      continue;
    }
    Status s = on_body(std::string_view(chunk.data(), got));
    if (!s.ok()) {
      keep_alive_ = false;
      co_return s;
    }
  }
  if (code != 200) {
    co_return StatusFromResponse(
        "GET " + target, code, std::string(parser.get().reason()), error_body);
  }
  co_return Status::Ok();
}

net::awaitable<Status> HttpClient::ExchangeOnce(const std::string& target,
                                                const std::string& accept,
                                                const HeadHandler& on_head,
                                                const BodyHandler& on_body,
                                                bool& got_head) {
  if (tls_)
    co_return co_await Exchange(*tls_, target, accept, on_head, on_body,
                                got_head);
  co_return co_await Exchange(*plain_, target, accept, on_head, on_body,
                              got_head);
}

net::awaitable<Status> HttpClient::Get(std::string target, std::string accept,
                                       HeadHandler on_head,
                                       BodyHandler on_body) {
  const bool reused = connected();
  if (!reused) MWC_CO_RETURN_IF_ERROR(co_await Connect());
  bool got_head = false;
  Status s = co_await ExchangeOnce(target, accept, on_head, on_body, got_head);
  if (!s.ok() && s.code() == StatusCode::kIoError && reused && !got_head) {
    // The server may have closed the idle keep-alive connection just as we
    // reused it: one fresh connection before counting this as a failure.
    MWC_CO_RETURN_IF_ERROR(co_await Connect());
    got_head = false;
    s = co_await ExchangeOnce(target, accept, on_head, on_body, got_head);
  }
  if (!s.ok() || !keep_alive_) Close();
  co_return s;
}

net::awaitable<Result<std::string>> HttpClient::GetBody(std::string target,
                                                        std::string accept,
                                                        uint64_t limit,
                                                        HeadHandler on_head) {
  std::string body;
  Status s = co_await Get(
      target, accept,
      [&](const http::response_header<>& head) {
        return on_head ? on_head(head) : Status::Ok();
      },
      [&](std::string_view bytes) {
        if (body.size() + bytes.size() > limit) {
          return ParseError("GET " + target + ": response larger than " +
                            std::to_string(limit) + " bytes");
        }
        body.append(bytes);
        return Status::Ok();
      });
  if (!s.ok()) co_return s;
  co_return body;
}

}  // namespace meshwave::client
