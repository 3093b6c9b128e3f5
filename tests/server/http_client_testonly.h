// A small synchronous Beast client for the server tests: one connection,
// requests built from parts or sent as raw bytes.
#ifndef MESHWAVE_TESTS_SERVER_HTTP_CLIENT_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_HTTP_CLIENT_TESTONLY_H_

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "net.h"

namespace meshwave::testing {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;

struct HttpReply {
  unsigned status = 0;  // 0: no response (connection closed or failed)
  std::map<std::string, std::string> headers;  // lowercase names
  std::string body;
  bool keep_alive = false;
  std::string Header(const std::string& name) const {
    auto it = headers.find(name);
    return it == headers.end() ? std::string() : it->second;
  }
};

class HttpConnection {
 public:
  explicit HttpConnection(uint16_t port) : socket_(ioc_) {
    beast::error_code ec;
    socket_.connect({net::ip::make_address("127.0.0.1"), port}, ec);
    connected_ = !ec;
  }
  bool connected() const { return connected_; }

  HttpReply Send(http::verb method, const std::string& target,
                 const std::vector<std::pair<std::string, std::string>>& headers = {},
                 const std::string& body = "") {
    http::request<http::string_body> req{method, target, 11};
    req.set(http::field::host, "127.0.0.1");
    for (const auto& [k, v] : headers) req.set(k, v);
    req.body() = body;
    if (!body.empty() || method == http::verb::post) req.prepare_payload();
    beast::error_code ec;
    http::write(socket_, req, ec);
    if (ec) return {};
    return Read(method == http::verb::head);
  }

  // Writes `raw` as it is and reads one response.
  HttpReply SendRaw(const std::string& raw) {
    beast::error_code ec;
    net::write(socket_, net::buffer(raw), ec);
    if (ec) return {};
    return Read(false);
  }

  // True once the server has closed the connection (reads EOF).
  bool ClosedByServer() {
    beast::error_code ec;
    char c;
    socket_.read_some(net::buffer(&c, 1), ec);
    return ec == net::error::eof || ec == net::error::connection_reset;
  }

 private:
  HttpReply Read(bool head) {
    http::response_parser<http::string_body> parser;
    parser.body_limit(boost::none);
    parser.skip(head);
    beast::error_code ec;
    http::read(socket_, buffer_, parser, ec);
    HttpReply r;
    if (ec) return r;
    const auto& res = parser.get();
    r.status = res.result_int();
    for (const auto& f : res) {
      std::string name(f.name_string());
      for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      r.headers[name] = std::string(f.value());
    }
    r.body = res.body();
    r.keep_alive = res.keep_alive();
    return r;
  }

  net::io_context ioc_;
  net::ip::tcp::socket socket_;
  beast::flat_buffer buffer_;
  bool connected_ = false;
};

inline HttpReply HttpGet(uint16_t port, const std::string& target,
                         const std::vector<std::pair<std::string, std::string>>& headers = {}) {
  HttpConnection c(port);
  return c.Send(http::verb::get, target, headers);
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_HTTP_CLIENT_TESTONLY_H_
