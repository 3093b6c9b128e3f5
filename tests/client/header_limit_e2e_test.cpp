// The client's --max-header holds on every path that receives a header,
// before the header is buffered: a hostile server that claims a 1 GiB
// header (in a WebSocket frame's length, or in GET /header's Content-Length
// on the --psnr path) and then offers its bytes as fast as the client takes
// them is refused at once. A client that buffered first would take 256 MiB
// here (or wait for the rest until its timeout).
#include <gtest/gtest.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#pragma GCC diagnostic pop

#include <atomic>
#include <chrono>
#include <iostream>
#include <string>
#include <thread>

#include "e2e/cli_runner.h"

namespace meshwave {
namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;
using testing::RunCli;
using testing::TempDir;

constexpr uint64_t kClaimed = uint64_t{1} << 30;
constexpr uint64_t kOffered = uint64_t{256} << 20;  // what it sends at most

// One connection at a time on 127.0.0.1: answers the WebSocket upgrade (or
// any HTTP GET), then claims a kClaimed-byte header and writes filler until
// the client goes away or kOffered bytes are out. Counts what it wrote.
class HugeHeaderServer {
 public:
  explicit HugeHeaderServer(bool websocket)
      : websocket_(websocket),
        acceptor_(ioc_, {net::ip::make_address("127.0.0.1"), 0}) {
    thread_ = std::thread([this] { Serve(); });
  }
  ~HugeHeaderServer() {
    stop_ = true;
    // Closing the acceptor does not wake a blocking accept(): a connection
    // does.
    net::io_context ioc;
    tcp::socket wake(ioc);
    beast::error_code ec;
    wake.connect({net::ip::make_address("127.0.0.1"), port()}, ec);
    thread_.join();
  }
  uint16_t port() const { return acceptor_.local_endpoint().port(); }
  uint64_t written() const { return written_; }
  int connections() const { return connections_; }

 private:
  void Serve() {
    while (!stop_) {
      beast::error_code ec;
      tcp::socket socket(ioc_);
      acceptor_.accept(socket, ec);
      if (ec || stop_) return;
      ++connections_;
      std::string head;
      if (websocket_) {
        websocket::stream<tcp::socket> ws(std::move(socket));
        ws.accept(ec);
        if (ec) continue;
        beast::flat_buffer request;
        ws.read(request, ec);  // the client's start
        if (ec) continue;
        // A binary frame, FIN, no mask, 64-bit length: kClaimed.
        head = std::string("\x82\x7f", 2);
        for (int shift = 56; shift >= 0; shift -= 8) {
          head.push_back(static_cast<char>((kClaimed >> shift) & 0xff));
        }
        Offer(ws.next_layer(), head);
      } else {
        beast::flat_buffer buffer;
        http::request<http::empty_body> req;
        http::read(socket, buffer, req, ec);
        if (ec) continue;
        if (req.target().find("/stream") != std::string_view::npos) {
          // A container whose length field claims kClaimed header bytes.
          head =
              "HTTP/1.1 200 OK\r\nX-Meshwave-Packets: "
              "1\r\nX-Meshwave-Next-Cursor: 1\r\n"
              "Content-Length: " +
              std::to_string(8 + kClaimed) + "\r\n\r\nMWV1";
          for (int shift = 0; shift < 32; shift += 8) {
            head.push_back(static_cast<char>((kClaimed >> shift) & 0xff));
          }
        } else {  // GET /header
          head =
              "HTTP/1.1 200 OK\r\nContent-Type: "
              "application/x-protobuf\r\nContent-Length: " +
              std::to_string(kClaimed) + "\r\n\r\n";
        }
        Offer(socket, head);
      }
    }
  }

  void Offer(tcp::socket& socket, const std::string& head) {
    beast::error_code ec;
    net::write(socket, net::buffer(head), ec);
    const std::string filler(64 * 1024, '\x0a');
    while (!ec && !stop_ && written_ < kOffered) {
      written_ += net::write(socket, net::buffer(filler), ec);
    }
    // Hold the connection until the client closes it (or the test ends).
    char byte;
    socket.non_blocking(true, ec);
    while (!stop_) {
      socket.read_some(net::buffer(&byte, 1), ec);
      if (ec && ec != net::error::would_block) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }

  bool websocket_;
  net::io_context ioc_;
  tcp::acceptor acceptor_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> written_{0};
  std::atomic<int> connections_{0};
};

struct Path {
  const char* name;
  bool websocket;
  std::vector<std::string> budget;  // the fetch's budget arguments
};

class HugeHeaderTest : public ::testing::TestWithParam<Path> {};

TEST_P(HugeHeaderTest, IsRefusedBeforeItIsBuffered) {
  const Path& path = GetParam();
  HugeHeaderServer server(path.websocket);
  TempDir dir;
  const std::string url = std::string(path.websocket ? "ws" : "http") +
                          "://127.0.0.1:" + std::to_string(server.port()) +
                          "/v1/meshes/0123456789ab";
  std::vector<std::string> args = {
      "fetch",     url,   "--max-header", "1MiB",
      "--timeout", "20s", "--out",        (dir / "m.ply").string()};
  args.insert(args.end(), path.budget.begin(), path.budget.end());
  const auto start = std::chrono::steady_clock::now();
  const auto r = RunCli(args);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
  std::cout << path.name << ": refused in " << static_cast<int>(seconds * 1000)
            << " ms; the server got " << server.written() << " of " << kOffered
            << " bytes out; " << r.err;
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("over this client's limit of 1048576"),
            std::string::npos)
      << r.err;
  // Final, not retried, and not after waiting for the claimed bytes.
  EXPECT_EQ(server.connections(), 1);
  EXPECT_LT(seconds, 10.0);
  // What the server got out is what the kernel's socket buffers hold, not
  // what the client read: far below the 256 MiB it offered.
  EXPECT_LT(server.written(), uint64_t{32} << 20)
      << server.written() << " bytes";
  EXPECT_FALSE(std::filesystem::exists(dir / "m.ply"));
}

std::string PathName(const ::testing::TestParamInfo<Path>& param) {
  return param.param.name;
}

INSTANTIATE_TEST_SUITE_P(
    Paths, HugeHeaderTest,
    ::testing::Values(Path{"WebSocketStart", true, {"--budget", "5000"}},
                      Path{"WebSocketPsnr", true, {"--psnr", "40"}},
                      Path{"HttpPsnr", false, {"--psnr", "40"}},
                      Path{"HttpStream", false, {"--budget", "5000"}}),
    PathName);

}  // namespace
}  // namespace meshwave
