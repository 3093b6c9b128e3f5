#include "http_client.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <vector>

#include "co_status.h"

namespace meshwave::client {
namespace {

constexpr size_t kChunkBytes = 64 * 1024;
constexpr size_t kErrorBodyLimit = 64 * 1024;

auto Tuple() { return net::as_tuple(net::use_awaitable); }

Status NetError(const std::string& what, const beast::error_code& ec,
                std::chrono::milliseconds timeout) {
  if (ec == beast::error::timeout) {
    return IoError(what + ": timed out after " +
                   std::to_string(timeout.count()) + " ms");
  }
  return IoError(what + ": " + ec.message());
}

// The "error" member of the server's JSON error body, else the body itself
// (shortened): what a person needs to see.
std::string ErrorMessage(const std::string& body) {
  google::protobuf::Struct json;
  if (google::protobuf::util::JsonStringToMessage(body, &json).ok()) {
    auto it = json.fields().find("error");
    if (it != json.fields().end() && it->second.has_string_value()) {
      return it->second.string_value();
    }
  }
  std::string text = body.substr(0, 200);
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return text.empty() ? "(no message)" : text;
}

Status StatusFromResponse(const std::string& target, unsigned code,
                          const std::string& reason, const std::string& body) {
  const std::string what = "GET " + target + ": " + std::to_string(code) + " " +
                           reason + ": " + ErrorMessage(body);
  if (code >= 500) return IoError(what);  // worth retrying
  if (code == 404) return Status(StatusCode::kNotFound, what);
  return InvalidArgument(what);
}

std::string HostHeader(const ServerUrl& s) {
  const bool v6 = s.host.find(':') != std::string::npos;
  const std::string host = v6 ? "[" + s.host + "]" : s.host;
  const bool default_port = s.port == (s.tls ? 443 : 80);
  return default_port ? host : host + ":" + std::to_string(s.port);
}

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
  const std::string where = server_.host + ":" + std::to_string(server_.port);
  tcp::resolver resolver(executor_);
  auto [rec, endpoints] = co_await resolver.async_resolve(
      server_.host, std::to_string(server_.port), Tuple());
  if (rec)
    co_return IoError("resolving " + server_.host + ": " + rec.message());

  if (!server_.tls) {
    plain_.emplace(executor_);
    plain_->expires_after(options_.connect_timeout);
    auto [ec, ep] = co_await plain_->async_connect(endpoints, Tuple());
    if (ec) {
      Close();
      co_return NetError("connecting to " + where, ec,
                         options_.connect_timeout);
    }
    plain_->socket().set_option(tcp::no_delay(true),
                                ec);  // small requests, no Nagle wait
    co_return Status::Ok();
  }

  if (!ssl_context_) {
    auto ctx = std::make_unique<ssl::context>(ssl::context::tls_client);
    ctx->set_verify_mode(ssl::verify_peer);
    beast::error_code ec;
    if (options_.ca_file.empty()) {
      ctx->set_default_verify_paths(ec);
    } else {
      ctx->load_verify_file(options_.ca_file, ec);
    }
    if (ec) {
      co_return InvalidArgument("TLS: cannot load the trusted certificates" +
                                (options_.ca_file.empty()
                                     ? std::string()
                                     : " from " + options_.ca_file) +
                                ": " + ec.message());
    }
    ssl_context_ = std::move(ctx);
  }
  tls_.emplace(executor_, *ssl_context_);
  auto& lowest = beast::get_lowest_layer(*tls_);
  lowest.expires_after(options_.connect_timeout);
  auto [ec, ep] = co_await lowest.async_connect(endpoints, Tuple());
  if (ec) {
    Close();
    co_return NetError("connecting to " + where, ec, options_.connect_timeout);
  }
  lowest.socket().set_option(tcp::no_delay(true), ec);
  // The certificate must name the host we asked for: OpenSSL checks it
  // during verification (an IP literal against the IP SANs), so a mismatch
  // is reported like any other verification failure. SNI for names only.
  SSL* ssl = tls_->native_handle();
  beast::error_code aec;
  net::ip::make_address(server_.host, aec);
  const bool is_ip = !aec;
  const int named = is_ip ? X509_VERIFY_PARAM_set1_ip_asc(SSL_get0_param(ssl),
                                                          server_.host.c_str())
                          : SSL_set1_host(ssl, server_.host.c_str());
  // SSL_set_tlsext_host_name without its macro's C cast.
  if (named != 1 ||
      (!is_ip &&
       SSL_ctrl(ssl, SSL_CTRL_SET_TLSEXT_HOSTNAME, TLSEXT_NAMETYPE_host_name,
                const_cast<char*>(server_.host.c_str())) != 1)) {
    Close();
    co_return IoError("TLS: cannot set the server name " + server_.host);
  }
  lowest.expires_after(options_.connect_timeout);
  auto [hec] =
      co_await tls_->async_handshake(ssl::stream_base::client, Tuple());
  if (hec) {
    const long verify = SSL_get_verify_result(tls_->native_handle());
    Close();
    if (verify != X509_V_OK) {
      // Retrying cannot help: the certificate is what it is.
      co_return InvalidArgument(
          "TLS: the certificate of " + where +
          " does not verify: " + X509_verify_cert_error_string(verify));
    }
    if (hec.category() == net::error::get_ssl_category()) {
      // A protocol failure (not TLS on the other end, no shared cipher):
      // the same on every try.
      co_return InvalidArgument("TLS handshake with " + where +
                                " failed: " + hec.message());
    }
    co_return NetError("TLS handshake with " + where, hec,
                       options_.connect_timeout);
  }
  co_return Status::Ok();
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
        target, code, std::string(parser.get().reason()), error_body);
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
                                                        uint64_t limit) {
  std::string body;
  Status s = co_await Get(
      target, accept,
      [](const http::response_header<>&) { return Status::Ok(); },
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
