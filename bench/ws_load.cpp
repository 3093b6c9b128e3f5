// ws_load: holds N concurrent paced WebSocket sessions on a meshwave-server
// for a while, on one thread (one io_context, one coroutine per session),
// and reports what each session received. Each session starts the stream
// of MESH at RATE bytes/s and, whenever the server says Done, asks for the
// same payloads again (resume from cursor 0), so it streams for as long as
// it is held. bench/ws_sessions.sh runs it against a server and samples the
// server's memory.
//
//   ws_load --port P --mesh ID [--sessions 2000] [--rate 8000]
//           [--seconds 60] [--ramp-per-second 1000]
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "websocket.pb.h"

namespace {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace websocket = boost::beast::websocket;
using tcp = net::ip::tcp;
using Clock = std::chrono::steady_clock;

struct Options {
  uint16_t port = 0;
  std::string mesh;
  int sessions = 2000;
  uint64_t rate = 8000;  // bytes/s per session
  double seconds = 60;
  int ramp_per_second = 1000;
};

struct SessionStats {
  bool connected = false;
  bool failed = false;
  std::string error;
  uint64_t bytes_total = 0;
  uint64_t bytes_held = 0;  // received while every session was held
  uint64_t messages = 0;
};

struct Shared {
  Options options;
  Clock::time_point hold_start{}, hold_end{};
  bool holding = false;
  bool stopping = false;
  std::vector<std::unique_ptr<websocket::stream<beast::tcp_stream>>> sockets;
};

auto Tuple() { return net::as_tuple(net::use_awaitable); }

std::string Serialize(const meshwave::proto::ClientMessage& m) {
  return m.SerializeAsString();
}

net::awaitable<void> RunSession(Shared& shared, size_t index,
                                SessionStats& stats) {
  auto& ws = *shared.sockets[index];
  auto fail = [&](const char* what, beast::error_code ec) {
    if (shared.stopping) return;
    stats.failed = true;
    stats.error = std::string(what) + ": " + ec.message();
  };
  auto [cec] = co_await beast::get_lowest_layer(ws).socket().async_connect(
      tcp::endpoint(net::ip::make_address("127.0.0.1"), shared.options.port),
      Tuple());
  if (cec) co_return fail("connect", cec);
  auto [hec] = co_await ws.async_handshake("127.0.0.1", "/v1/ws", Tuple());
  if (hec) co_return fail("handshake", hec);
  stats.connected = true;
  ws.binary(true);
  meshwave::proto::ClientMessage start;
  start.mutable_start()->set_mesh_id(shared.options.mesh);
  start.mutable_start()->set_rate(shared.options.rate);
  meshwave::proto::ClientMessage again;
  again.mutable_resume()->set_mesh_id(shared.options.mesh);
  again.mutable_resume()->set_cursor(0);
  again.mutable_resume()->set_rate(shared.options.rate);
  const std::string start_bytes = Serialize(start);
  const std::string again_bytes = Serialize(again);
  auto [wec, wn] = co_await ws.async_write(net::buffer(start_bytes), Tuple());
  if (wec) co_return fail("write", wec);
  beast::flat_buffer buffer;
  meshwave::proto::ServerMessage m;
  for (;;) {
    buffer.clear();
    auto [rec, n] = co_await ws.async_read(buffer, Tuple());
    if (rec) co_return fail("read", rec);
    ++stats.messages;
    stats.bytes_total += n;
    if (shared.holding) stats.bytes_held += n;
    const auto data = buffer.cdata();
    if (!m.ParseFromArray(data.data(), static_cast<int>(data.size()))) {
      stats.failed = true;
      stats.error = "a message that does not parse";
      co_return;
    }
    if (m.has_error()) {
      stats.failed = true;
      stats.error = "server error: " + m.error().message();
      co_return;
    }
    if (m.has_done()) {
      // The whole order sent: the same payloads again, still paced.
      auto [aec, an] =
          co_await ws.async_write(net::buffer(again_bytes), Tuple());
      if (aec) co_return fail("write", aec);
    }
  }
}

bool ParseArgs(int argc, char** argv, Options& o) {
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--port") {
      o.port = static_cast<uint16_t>(std::stoi(v));
    } else if (k == "--mesh") {
      o.mesh = v;
    } else if (k == "--sessions") {
      o.sessions = std::stoi(v);
    } else if (k == "--rate") {
      o.rate = std::stoull(v);
    } else if (k == "--seconds") {
      o.seconds = std::stod(v);
    } else if (k == "--ramp-per-second") {
      o.ramp_per_second = std::max(1, std::stoi(v));
    } else {
      return false;
    }
  }
  return o.port != 0 && !o.mesh.empty() && o.sessions > 0;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!ParseArgs(argc, argv, options)) {
    std::fprintf(stderr,
                 "usage: ws_load --port P --mesh ID [--sessions N] [--rate "
                 "B/s] [--seconds S] [--ramp-per-second N]\n");
    return 2;
  }
  // The io_context first: it must outlive the sockets in `shared`.
  net::io_context ioc(1);
  Shared shared;
  shared.options = options;
  const Options& o = shared.options;
  std::vector<SessionStats> stats(static_cast<size_t>(o.sessions));
  for (int i = 0; i < o.sessions; ++i) {
    shared.sockets.push_back(
        std::make_unique<websocket::stream<beast::tcp_stream>>(ioc));
  }
  // Sessions start in steps of 10 ms so that the accept queue never
  // overflows; the hold begins once all are started and streaming.
  const auto start = Clock::now();
  net::co_spawn(
      ioc,
      [&]() -> net::awaitable<void> {
        net::steady_timer timer(ioc);
        const int per_step = std::max(1, o.ramp_per_second / 100);
        for (int i = 0; i < o.sessions; ++i) {
          net::co_spawn(ioc,
                        RunSession(shared, static_cast<size_t>(i),
                                   stats[static_cast<size_t>(i)]),
                        net::detached);
          if ((i + 1) % per_step == 0) {
            timer.expires_after(std::chrono::milliseconds(10));
            co_await timer.async_wait(net::use_awaitable);
          }
        }
        timer.expires_after(std::chrono::seconds(1));  // all connected
        co_await timer.async_wait(net::use_awaitable);
        int connected = 0;
        for (const auto& s : stats) connected += s.connected;
        std::printf(
            "ramp: %d of %d sessions open after %.1f s\n", connected,
            o.sessions,
            std::chrono::duration<double>(Clock::now() - start).count());
        std::fflush(stdout);
        shared.holding = true;
        shared.hold_start = Clock::now();
        timer.expires_after(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(o.seconds)));
        co_await timer.async_wait(net::use_awaitable);
        shared.holding = false;
        shared.hold_end = Clock::now();
        shared.stopping = true;
        for (auto& ws : shared.sockets) {
          beast::error_code ec;
          beast::get_lowest_layer(*ws).socket().close(ec);
        }
      },
      net::detached);
  ioc.run();

  const double held =
      std::chrono::duration<double>(shared.hold_end - shared.hold_start)
          .count();
  int connected = 0, failed = 0, alive = 0;
  uint64_t total = 0;
  std::vector<double> rates;
  std::string first_error;
  for (const auto& s : stats) {
    connected += s.connected;
    failed += s.failed;
    if (s.failed && first_error.empty()) first_error = s.error;
    if (s.connected && !s.failed) ++alive;
    total += s.bytes_held;
    if (s.connected) rates.push_back(static_cast<double>(s.bytes_held) / held);
  }
  std::printf(
      "sessions %d, connected %d, alive at the end %d, failed %d%s%s\n"
      "held %.1f s at %llu B/s each: received %.1f MB, %.2f MB/s in all\n"
      "per-session rate B/s: min %.0f, median %.0f, max %.0f\n",
      o.sessions, connected, alive, failed, first_error.empty() ? "" : ": ",
      first_error.c_str(), held, static_cast<unsigned long long>(o.rate),
      static_cast<double>(total) / 1e6, static_cast<double>(total) / 1e6 / held,
      Percentile(rates, 0), Percentile(rates, 0.5), Percentile(rates, 1));
  return failed == 0 && connected == o.sessions ? 0 : 1;
}
