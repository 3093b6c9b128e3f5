#include "server_connection.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

namespace meshwave::client {
namespace {

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

}  // namespace

Status NetError(const std::string& what, const beast::error_code& ec,
                std::chrono::milliseconds timeout) {
  if (ec == beast::error::timeout) {
    return IoError(what + ": timed out after " +
                   std::to_string(timeout.count()) + " ms");
  }
  return IoError(what + ": " + ec.message());
}

std::string HostHeader(const ServerUrl& s) {
  const bool v6 = s.host.find(':') != std::string::npos;
  const std::string host = v6 ? "[" + s.host + "]" : s.host;
  const bool default_port = s.port == (s.tls ? 443 : 80);
  return default_port ? host : host + ":" + std::to_string(s.port);
}

Status StatusFromResponse(const std::string& what, unsigned code,
                          const std::string& reason, const std::string& body) {
  const std::string text = what + ": " + std::to_string(code) + " " + reason +
                           ": " + ErrorMessage(body);
  if (code >= 500) return IoError(text);  // worth retrying
  if (code == 404) return Status(StatusCode::kNotFound, text);
  if (code == 409) return Status(StatusCode::kStale, text);  // the mesh was re-encoded
  return InvalidArgument(text);
}

net::awaitable<Status> ConnectTcp(beast::tcp_stream& stream,
                                  const ServerUrl& server,
                                  const TransportOptions& options) {
  const std::string where = server.host + ":" + std::to_string(server.port);
  tcp::resolver resolver(stream.get_executor());
  auto [rec, endpoints] = co_await resolver.async_resolve(
      server.host, std::to_string(server.port), Tuple());
  if (rec) co_return IoError("resolving " + server.host + ": " + rec.message());
  stream.expires_after(options.connect_timeout);
  auto [ec, ep] = co_await stream.async_connect(endpoints, Tuple());
  if (ec) {
    co_return NetError("connecting to " + where, ec, options.connect_timeout);
  }
  stream.socket().set_option(tcp::no_delay(true), ec);  // small requests
  co_return Status::Ok();
}

Result<std::unique_ptr<ssl::context>> MakeTlsContext(
    const TransportOptions& options) {
  auto ctx = std::make_unique<ssl::context>(ssl::context::tls_client);
  ctx->set_verify_mode(ssl::verify_peer);
  beast::error_code ec;
  if (options.ca_file.empty()) {
    ctx->set_default_verify_paths(ec);
  } else {
    ctx->load_verify_file(options.ca_file, ec);
  }
  if (ec) {
    return InvalidArgument(
        "TLS: cannot load the trusted certificates" +
        (options.ca_file.empty() ? std::string() : " from " + options.ca_file) +
        ": " + ec.message());
  }
  return ctx;
}

net::awaitable<Status> ConnectTls(beast::ssl_stream<beast::tcp_stream>& stream,
                                  const ServerUrl& server,
                                  const TransportOptions& options) {
  const std::string where = server.host + ":" + std::to_string(server.port);
  auto& lowest = beast::get_lowest_layer(stream);
  Status connected = co_await ConnectTcp(lowest, server, options);
  if (!connected.ok()) co_return connected;
  // The certificate must name the host we asked for: OpenSSL checks it
  // during verification (an IP literal against the IP SANs), so a mismatch
  // is reported like any other verification failure. SNI for names only.
  SSL* ssl = stream.native_handle();
  beast::error_code aec;
  net::ip::make_address(server.host, aec);
  const bool is_ip = !aec;
  const int named = is_ip ? X509_VERIFY_PARAM_set1_ip_asc(SSL_get0_param(ssl),
                                                          server.host.c_str())
                          : SSL_set1_host(ssl, server.host.c_str());
  // SSL_set_tlsext_host_name without its macro's C cast.
  if (named != 1 ||
      (!is_ip &&
       SSL_ctrl(ssl, SSL_CTRL_SET_TLSEXT_HOSTNAME, TLSEXT_NAMETYPE_host_name,
                const_cast<char*>(server.host.c_str())) != 1)) {
    co_return IoError("TLS: cannot set the server name " + server.host);
  }
  lowest.expires_after(options.connect_timeout);
  auto [hec] =
      co_await stream.async_handshake(ssl::stream_base::client, Tuple());
  if (hec) {
    const long verify = SSL_get_verify_result(stream.native_handle());
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
                       options.connect_timeout);
  }
  co_return Status::Ok();
}

}  // namespace meshwave::client
