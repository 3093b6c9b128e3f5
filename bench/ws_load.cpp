// ws_load: holds N concurrent paced WebSocket sessions on a meshwave-server
// for a while, on one thread (one io_context, one coroutine per session),
// and reports what each session received. Each session starts the stream
// of MESH at RATE bytes/s and, whenever the server says Done, asks for the
// same payloads again (resume from cursor 0), so it streams for as long as
// it is held. bench/ws_sessions.sh runs it against a server and samples the
// server's memory.
//
// With --budget B --refine R a session starts with a budget of B bytes and,
// each time the server stops at the budget, asks for R more on the same
// socket (refine); once the order is complete it closes the connection and
// opens a new session (bench/soak.sh: sessions come and go). Every packet's
// cursor is checked to follow the previous one.
//
//   ws_load --port P --mesh ID [--sessions 2000] [--rate 8000]
//           [--seconds 60] [--ramp-per-second 1000]
//           [--budget B --refine R]
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
  uint64_t budget = 0;  // 0: the whole order, resumed from 0 at each Done
  uint64_t refine = 0;  // with budget: refine by this much, reconnect when complete
};

struct SessionStats {
  bool connected = false;
  bool failed = false;
  std::string error;
  uint64_t bytes_total = 0;
  uint64_t bytes_held = 0;  // received while every session was held
  uint64_t messages = 0;
  uint64_t connections = 0;  // sessions opened (more than 1 with --refine)
  uint64_t refines = 0;
  uint64_t completed = 0;  // orders received to the end
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
  const Options& o = shared.options;
  auto fail = [&](const std::string& what, beast::error_code ec) {
    if (shared.stopping) return;
    stats.failed = true;
    stats.error = what + ": " + ec.message();
  };
  meshwave::proto::ClientMessage start;
  start.mutable_start()->set_mesh_id(o.mesh);
  start.mutable_start()->set_rate(o.rate);
  if (o.budget > 0) start.mutable_start()->set_budget(o.budget);
  meshwave::proto::ClientMessage again;
  again.mutable_resume()->set_mesh_id(o.mesh);
  again.mutable_resume()->set_cursor(0);
  again.mutable_resume()->set_rate(o.rate);
  meshwave::proto::ClientMessage refine;
  refine.mutable_refine()->set_extra_bytes(o.refine);
  const std::string start_bytes = Serialize(start);
  const std::string again_bytes = Serialize(again);
  const std::string refine_bytes = Serialize(refine);
  const bool refining = o.budget > 0 && o.refine > 0;
  while (!shared.stopping) {
    auto& ws = *shared.sockets[index];
    auto [cec] = co_await beast::get_lowest_layer(ws).socket().async_connect(
        tcp::endpoint(net::ip::make_address("127.0.0.1"), o.port), Tuple());
    if (cec) co_return fail("connect", cec);
    auto [hec] = co_await ws.async_handshake("127.0.0.1", "/v1/ws", Tuple());
    if (hec) co_return fail("handshake", hec);
    stats.connected = true;
    ++stats.connections;
    ws.binary(true);
    auto [wec, wn] = co_await ws.async_write(net::buffer(start_bytes), Tuple());
    if (wec) co_return fail("write", wec);
    beast::flat_buffer buffer;
    meshwave::proto::ServerMessage m;
    uint32_t next_cursor = 0;  // of the next packet expected
    bool complete = false;
    while (!complete) {
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
      if (m.has_packet()) {
        if (m.packet().cursor() != next_cursor) {
          stats.failed = true;
          stats.error = "packet cursor " + std::to_string(m.packet().cursor()) +
                        " where " + std::to_string(next_cursor) + " was due";
          co_return;
        }
        ++next_cursor;
      }
      if (!m.has_done()) continue;
      const std::string* next = &again_bytes;
      if (refining) {
        if (m.done().complete()) {
          ++stats.completed;
          complete = true;
          break;
        }
        ++stats.refines;
        next = &refine_bytes;
      } else {
        ++stats.completed;
        next_cursor = 0;  // the same payloads again, still paced
      }
      auto [aec, an] = co_await ws.async_write(net::buffer(*next), Tuple());
      if (aec) co_return fail("write", aec);
    }
    // The order received to its end: close, and a new session.
    auto [clec] = co_await ws.async_close(websocket::close_code::normal, Tuple());
    if (clec && !shared.stopping) co_return fail("close", clec);
    if (shared.stopping) co_return;
    shared.sockets[index] =
        std::make_unique<websocket::stream<beast::tcp_stream>>(
            ws.get_executor());
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
    } else if (k == "--budget") {
      o.budget = std::stoull(v);
    } else if (k == "--refine") {
      o.refine = std::stoull(v);
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
                 "B/s] [--seconds S] [--ramp-per-second N] [--budget B "
                 "--refine R]\n");
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
  uint64_t total = 0, connections = 0, refines = 0, completed = 0;
  std::vector<double> rates;
  std::string first_error;
  for (const auto& s : stats) {
    connected += s.connected;
    failed += s.failed;
    if (s.failed && first_error.empty()) first_error = s.error;
    if (s.connected && !s.failed) ++alive;
    total += s.bytes_held;
    connections += s.connections;
    refines += s.refines;
    completed += s.completed;
    if (s.connected) rates.push_back(static_cast<double>(s.bytes_held) / held);
  }
  std::printf(
      "sessions %d, connected %d, alive at the end %d, failed %d%s%s\n"
      "held %.1f s at %llu B/s each: received %.1f MB, %.2f MB/s in all\n"
      "per-session rate B/s: min %.0f, median %.0f, max %.0f\n"
      "ws_sessions_opened %llu\nws_refines %llu\nws_orders_completed %llu\n"
      "ws_failed %d\n",
      o.sessions, connected, alive, failed, first_error.empty() ? "" : ": ",
      first_error.c_str(), held, static_cast<unsigned long long>(o.rate),
      static_cast<double>(total) / 1e6, static_cast<double>(total) / 1e6 / held,
      Percentile(rates, 0), Percentile(rates, 0.5), Percentile(rates, 1),
      static_cast<unsigned long long>(connections),
      static_cast<unsigned long long>(refines),
      static_cast<unsigned long long>(completed), failed);
  return failed == 0 && connected == o.sessions ? 0 : 1;
}
