// https and wss: a local TLS listener with a certificate made in the test.
// Without trusting it the client refuses it (clear message, no retry);
// trusting it with a CA file works; a certificate for another host name is
// refused. The same for a WebSocket session over wss://.
#include <gtest/gtest.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <atomic>
#include <cstdio>
#include <thread>

#include "e2e/cli_runner.h"
#include "meshwave/client/blocking_session.h"
#include "meshwave/client/catalog.h"
#include "net.h"
#include "websocket.pb.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#pragma GCC diagnostic pop

namespace meshwave::client {
namespace {

using testing::TempDir;

// Writes a self-signed P-256 certificate for `san` (e.g. "IP:127.0.0.1")
// and its key as PEM files.
bool MakeCertificate(const std::string& san, const std::filesystem::path& cert,
                     const std::filesystem::path& key) {
  EVP_PKEY* pkey = EVP_EC_gen("P-256");
  X509* x = X509_new();
  if (pkey == nullptr || x == nullptr) return false;
  X509_set_version(x, 2);
  ASN1_INTEGER_set(X509_get_serialNumber(x), 1);
  X509_gmtime_adj(X509_getm_notBefore(x), -60);
  X509_gmtime_adj(X509_getm_notAfter(x), 3600);
  X509_set_pubkey(x, pkey);
  X509_NAME* name = X509_get_subject_name(x);
  X509_NAME_add_entry_by_txt(
      name, "CN", MBSTRING_ASC,
      reinterpret_cast<const unsigned char*>("meshwave test"), -1, -1, 0);
  X509_set_issuer_name(x, name);
  X509V3_CTX ctx;
  X509V3_set_ctx_nodb(&ctx);
  X509V3_set_ctx(&ctx, x, x, nullptr, nullptr, 0);
  X509_EXTENSION* ext =
      X509V3_EXT_conf_nid(nullptr, &ctx, NID_subject_alt_name, san.c_str());
  X509_add_ext(x, ext, -1);
  X509_EXTENSION_free(ext);
  ext = X509V3_EXT_conf_nid(nullptr, &ctx, NID_basic_constraints,
                            "critical,CA:TRUE");
  X509_add_ext(x, ext, -1);
  X509_EXTENSION_free(ext);
  const bool signed_ok = X509_sign(x, pkey, EVP_sha256()) > 0;
  FILE* c = std::fopen(cert.c_str(), "w");
  FILE* k = std::fopen(key.c_str(), "w");
  const bool ok =
      signed_ok && c && k && PEM_write_X509(c, x) &&
      PEM_write_PrivateKey(k, pkey, nullptr, nullptr, 0, nullptr, nullptr);
  if (c) std::fclose(c);
  if (k) std::fclose(k);
  X509_free(x);
  EVP_PKEY_free(pkey);
  return ok;
}

// Answers every GET with a one-mesh MeshList over TLS, one connection at a
// time; with `websocket`, accepts a WebSocket upgrade instead and answers
// the first message with a NOT_FOUND error (enough to show that the
// client's messages cross TLS).
class TlsListener {
 public:
  TlsListener(const std::filesystem::path& cert,
              const std::filesystem::path& key, bool websocket = false)
      : websocket_(websocket),
        ctx_(ssl::context::tls_server),
        acceptor_(io_, {net::ip::make_address("127.0.0.1"), 0}) {
    ctx_.use_certificate_chain_file(cert.string());
    ctx_.use_private_key_file(key.string(), ssl::context::pem);
    port_ = acceptor_.local_endpoint().port();
    thread_ = std::thread([this] { Serve(); });
  }
  ~TlsListener() {
    stop_ = true;
    beast::error_code ec;
    tcp::socket poke(io_);
    poke.connect({net::ip::make_address("127.0.0.1"), port_},
                 ec);  // wakes accept()
    thread_.join();
  }
  uint16_t port() const { return port_; }

 private:
  void Serve() {
    proto::MeshList list;
    list.add_meshes()->set_id("0123456789ab");
    list.set_total(1);
    while (!stop_) {
      tcp::socket socket(io_);
      beast::error_code ec;
      acceptor_.accept(socket, ec);
      if (ec || stop_) break;
      if (websocket_) {
        ServeWebSocket(std::move(socket));
        continue;
      }
      ssl::stream<tcp::socket> stream(std::move(socket), ctx_);
      stream.handshake(ssl::stream_base::server, ec);
      if (ec) continue;  // the client refused our certificate
      beast::flat_buffer buffer;
      http::request<http::string_body> req;
      http::read(stream, buffer, req, ec);
      if (ec) continue;
      http::response<http::string_body> res{http::status::ok, 11};
      res.body() = list.SerializeAsString();
      res.keep_alive(false);
      res.prepare_payload();
      http::write(stream, res, ec);
      stream.shutdown(ec);
    }
  }

  void ServeWebSocket(tcp::socket socket) {
    namespace websocket = beast::websocket;
    websocket::stream<ssl::stream<tcp::socket>> ws(std::move(socket), ctx_);
    beast::error_code ec;
    ws.next_layer().handshake(ssl::stream_base::server, ec);
    if (ec) return;  // the client refused our certificate
    ws.accept(ec);
    if (ec) return;
    beast::flat_buffer buffer;
    ws.read(buffer, ec);
    proto::ClientMessage request;
    const auto data = buffer.cdata();
    if (ec ||
        !request.ParseFromArray(data.data(), static_cast<int>(data.size()))) {
      return;
    }
    proto::ServerMessage reply;
    reply.mutable_error()->set_code(proto::Error::NOT_FOUND);
    reply.mutable_error()->set_message("no mesh " + request.start().mesh_id() +
                                       " over wss");
    ws.binary(true);
    ws.write(net::buffer(reply.SerializeAsString()), ec);
    ws.close(websocket::close_code::normal, ec);
  }

  const bool websocket_;
  net::io_context io_;
  ssl::context ctx_;
  tcp::acceptor acceptor_;
  uint16_t port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(TlsTest, RefusesAnUntrustedCertificateWithAClearMessage) {
  TempDir dir;
  ASSERT_TRUE(
      MakeCertificate("IP:127.0.0.1", dir / "cert.pem", dir / "key.pem"));
  TlsListener listener(dir / "cert.pem", dir / "key.pem");
  auto url =
      ParseServerUrl("https://127.0.0.1:" + std::to_string(listener.port()));
  ASSERT_TRUE(url.ok());
  auto list = ListCatalog(*url, TransportOptions{});
  ASSERT_FALSE(list.ok());
  EXPECT_EQ(list.status().code(),
            StatusCode::kInvalidArgument);  // final, not retried
  EXPECT_NE(list.status().message().find("does not verify"), std::string::npos)
      << list.status().message();
  EXPECT_NE(list.status().message().find("self-signed"), std::string::npos)
      << list.status().message();
}

TEST(TlsTest, TrustsACertificateFromACaFile) {
  TempDir dir;
  ASSERT_TRUE(
      MakeCertificate("IP:127.0.0.1", dir / "cert.pem", dir / "key.pem"));
  TlsListener listener(dir / "cert.pem", dir / "key.pem");
  TransportOptions options;
  options.ca_file = (dir / "cert.pem").string();
  auto list = ListCatalog(
      *ParseServerUrl("https://127.0.0.1:" + std::to_string(listener.port())),
      options);
  ASSERT_TRUE(list.ok()) << list.status().ToString();
  ASSERT_EQ(list->meshes_size(), 1);
  EXPECT_EQ(list->meshes(0).id(), "0123456789ab");
}

TEST(TlsTest, RefusesACertificateForAnotherHost) {
  TempDir dir;
  ASSERT_TRUE(
      MakeCertificate("DNS:other.example", dir / "cert.pem", dir / "key.pem"));
  TlsListener listener(dir / "cert.pem", dir / "key.pem");
  TransportOptions options;
  options.ca_file = (dir / "cert.pem").string();
  auto list = ListCatalog(
      *ParseServerUrl("https://127.0.0.1:" + std::to_string(listener.port())),
      options);
  ASSERT_FALSE(list.ok());
  EXPECT_NE(list.status().message().find("mismatch"), std::string::npos)
      << list.status().message();
}

TEST(TlsTest, AMissingCaFileIsAClearError) {
  auto list = ListCatalog(*ParseServerUrl("https://127.0.0.1:9"),
                          TransportOptions{.ca_file = "/nonexistent/ca.pem"});
  ASSERT_FALSE(list.ok());
  EXPECT_NE(list.status().message().find("/nonexistent/ca.pem"),
            std::string::npos);
}

// A WebSocket session over wss://127.0.0.1:port.
Status FetchOverWss(uint16_t port, const TransportOptions& options) {
  auto url = ParseMeshUrl("wss://127.0.0.1:" + std::to_string(port) +
                          "/v1/meshes/0123456789ab");
  EXPECT_TRUE(url.ok());
  SessionOptions session;
  session.retry.max_attempts = 1;
  BlockingSession blocking(*url, session, options);
  return blocking.Fetch(Budget::Bytes(4000));
}

TEST(TlsTest, WssVerifiesTheCertificateLikeHttps) {
  TempDir dir;
  ASSERT_TRUE(
      MakeCertificate("IP:127.0.0.1", dir / "cert.pem", dir / "key.pem"));
  TlsListener listener(dir / "cert.pem", dir / "key.pem", /*websocket=*/true);
  Status s = FetchOverWss(listener.port(), TransportOptions{});
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("does not verify"), std::string::npos)
      << s.message();

  // Trusted: the handshake, the upgrade and our start message go through,
  // and the listener's answer comes back.
  TransportOptions trusted;
  trusted.ca_file = (dir / "cert.pem").string();
  s = FetchOverWss(listener.port(), trusted);
  EXPECT_EQ(s.code(), StatusCode::kNotFound) << s.ToString();
  EXPECT_NE(s.message().find("no mesh 0123456789ab over wss"),
            std::string::npos)
      << s.message();
}

TEST(TlsTest, WssRefusesACertificateForAnotherHost) {
  TempDir dir;
  ASSERT_TRUE(
      MakeCertificate("DNS:other.example", dir / "cert.pem", dir / "key.pem"));
  TlsListener listener(dir / "cert.pem", dir / "key.pem", /*websocket=*/true);
  TransportOptions options;
  options.ca_file = (dir / "cert.pem").string();
  const Status s = FetchOverWss(listener.port(), options);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("mismatch"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace meshwave::client
