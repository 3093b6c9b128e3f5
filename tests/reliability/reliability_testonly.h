// Helpers of the fault and abuse tests: a catalog of sample meshes
// (sample_catalog_testonly.h), the server started with a config file, raw
// sockets, and the server's resident memory and descriptor count from /proc.
#ifndef MESHWAVE_TESTS_RELIABILITY_RELIABILITY_TESTONLY_H_
#define MESHWAVE_TESTS_RELIABILITY_RELIABILITY_TESTONLY_H_

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "sample_catalog_testonly.h"
#include "server_process_testonly.h"
#include "test_data.h"

namespace meshwave::testing {

inline constexpr char kToken[] = "reliability-token-42";

// prefix + decimal i (spelled out: GCC 12's -Wrestrict misfires on
// `"literal" + std::to_string(i)`, GCC bug 105329).
inline std::string Numbered(std::string prefix, long i) {
  prefix += std::to_string(i);
  return prefix;
}

// Starts the server with `config` (protobuf text) and the upload token.
inline std::unique_ptr<ServerProcess> StartServer(const std::filesystem::path& catalog,
                                                  const std::filesystem::path& work,
                                                  const std::string& config = "") {
  std::vector<std::string> extra;
  if (!config.empty()) {
    std::ofstream(work / "server.conf") << config;
    extra = {"--config", (work / "server.conf").string()};
  }
  return std::make_unique<ServerProcess>(
      catalog, work, std::vector<std::string>{std::string("MESHWAVE_UPLOAD_TOKEN=") + kToken},
      extra);
}

// Resident set size of `pid` in KiB (VmRSS), -1 when unreadable.
inline long RssKib(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      long kib = -1;
      in >> kib;
      return kib;
    }
    std::getline(in, key);
  }
  return -1;
}

inline long FdCount(pid_t pid) {
  long n = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/fd", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    ++n;
  }
  return ec ? -1 : n;
}

inline bool Alive(pid_t pid) { return pid > 0 && ::kill(pid, 0) == 0; }

// A blocking TCP socket to the server, optionally from another loopback
// address (127.0.0.2 is a different client for per-client limits).
class RawSocket {
 public:
  explicit RawSocket(uint16_t port, const char* from = nullptr) : socket_(ioc_) {
    beast::error_code ec;
    socket_.open(net::ip::tcp::v4(), ec);
    if (from) socket_.bind({net::ip::make_address(from), 0}, ec);
    if (!ec) socket_.connect({net::ip::make_address("127.0.0.1"), port}, ec);
    connected_ = !ec;
  }
  bool connected() const { return connected_; }
  bool Write(std::string_view bytes) {
    beast::error_code ec;
    net::write(socket_, net::buffer(bytes.data(), bytes.size()), ec);
    return !ec;
  }
  // Everything until the server closes (or `limit` bytes).
  std::string ReadAll(size_t limit = 1 << 20) {
    std::string out;
    char buf[4096];
    beast::error_code ec;
    while (out.size() < limit) {
      const size_t n = socket_.read_some(net::buffer(buf), ec);
      out.append(buf, n);
      if (ec) break;
    }
    return out;
  }
  // True when the server has closed its side: a non-blocking read sees
  // EOF or a reset (pending response bytes are skipped).
  bool ClosedByPeer() {
    beast::error_code ec;
    socket_.non_blocking(true, ec);
    char buf[4096];
    for (;;) {
      socket_.read_some(net::buffer(buf), ec);
      if (ec == net::error::would_block) return false;
      if (ec) return true;
    }
  }
  net::ip::tcp::socket& socket() { return socket_; }

 private:
  net::io_context ioc_;
  net::ip::tcp::socket socket_;
  bool connected_ = false;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_RELIABILITY_RELIABILITY_TESTONLY_H_
