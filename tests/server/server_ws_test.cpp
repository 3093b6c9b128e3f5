// GET /v1/ws against the real meshwave-server on 127.0.0.1: streams compared
// byte for byte with GET /stream, pacing measured, Refine and Resume,
// refusals (bad requests, oversize and text messages, upgrade limits),
// keep-alive pings and the close on shutdown.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <cmath>

#include <fstream>
#include <map>
#include <thread>

#include "catalog_api.pb.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "meshwave/container.h"
#include "sample_catalog_testonly.h"
#include "server_process_testonly.h"
#include "test_data.h"
#include "ws_client_testonly.h"

namespace meshwave::testing {
namespace {

proto::ClientMessage StartMessage(const std::string& id,
                                  const std::string& order,
                                  std::optional<uint64_t> budget = std::nullopt,
                                  uint64_t rate = 0) {
  proto::ClientMessage m;
  auto* s = m.mutable_start();
  s->set_mesh_id(id);
  s->set_order(order);
  if (budget) s->set_budget(*budget);
  s->set_rate(rate);
  return m;
}

proto::ClientMessage RefineMessage(uint64_t extra) {
  proto::ClientMessage m;
  m.mutable_refine()->set_extra_bytes(extra);
  return m;
}

proto::ClientMessage ResumeMessage(const std::string& id,
                                   const std::string& order, uint32_t cursor,
                                   std::optional<uint64_t> budget) {
  proto::ClientMessage m;
  auto* r = m.mutable_resume();
  r->set_mesh_id(id);
  r->set_order(order);
  r->set_cursor(cursor);
  if (budget) r->set_budget(*budget);
  return m;
}

// What one request brought: the messages in order, checked for shape.
struct Received {
  std::optional<std::string> header;  // StreamStart's
  proto::Selection selection;
  std::vector<proto::Packet> packets;
  std::optional<proto::Done> done;
  std::optional<proto::Error> error;

  std::string Payloads() const {
    std::string out;
    for (const auto& p : packets) out += p.payload();
    return out;
  }
  std::vector<uint32_t> Ids() const {
    std::vector<uint32_t> ids;
    for (const auto& p : packets) ids.push_back(p.id());
    return ids;
  }
  // The /stream body from cursor 0: the container of these packets.
  std::string Container() const {
    return SerializeContainerHead(*header, Ids()) + Payloads();
  }
};

Received Collect(const std::vector<proto::ServerMessage>& messages) {
  Received r;
  for (const auto& m : messages) {
    if (m.has_start()) {
      EXPECT_FALSE(r.header.has_value());
      r.header = m.start().header();
      r.selection = m.start().selection();
    } else if (m.has_selection()) {
      r.selection = m.selection();
    } else if (m.has_packet()) {
      EXPECT_EQ(m.packet().cursor(),
                r.selection.from_cursor() + r.packets.size());
      r.packets.push_back(m.packet());
    } else if (m.has_done()) {
      r.done = m.done();
    } else if (m.has_error()) {
      r.error = m.error();
    }
  }
  return r;
}

Received Exchange(WsTestClient& c, const proto::ClientMessage& m) {
  EXPECT_TRUE(c.Send(m));
  return Collect(c.ReadUntilDone());
}

// A server on a catalog of the two sample meshes, shared by the tests; a test that
// needs other settings starts its own on the same catalog.
class ServerWsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    catalog_ = *dir_ / "catalog";
    ASSERT_NO_FATAL_FAILURE(
        CopySampleCatalog(catalog_, {SampleMesh("elephant.off"), SampleMesh("holes.off")}));
    std::filesystem::create_directories(*dir_ / "server");
    server_ = new ServerProcess(catalog_, *dir_ / "server");
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    const HttpReply list = HttpGet(server_->port(), "/v1/meshes");
    proto::MeshList meshes;
    ASSERT_TRUE(
        google::protobuf::util::JsonStringToMessage(list.body, &meshes).ok());
    for (const auto& m : meshes.meshes()) (*ids_)[m.name()] = m.id();
    ASSERT_EQ(ids_->size(), 2u) << list.body;
  }
  static void TearDownTestSuite() {
    if (server_) {
      EXPECT_EQ(server_->Stop(), 0) << ReadBytes(server_->log());
    }
    delete server_;
    delete dir_;
  }

  static uint16_t port() { return server_->port(); }
  static const std::string& Id(const std::string& name) {
    return ids_->at(name);
  }
  static HttpReply Stream(const std::string& id, const std::string& query) {
    return HttpGet(port(), "/v1/meshes/" + id + "/stream?" + query);
  }
  // A second server on the same catalog with `config` (text format).
  static std::unique_ptr<ServerProcess> StartServer(const std::string& name,
                                                    const std::string& config) {
    const auto work = *dir_ / name;
    std::filesystem::create_directories(work);
    std::ofstream(work / "server.conf") << config;
    return std::make_unique<ServerProcess>(
        catalog_, work, std::vector<std::string>{},
        std::vector<std::string>{"--config", (work / "server.conf").string()});
  }

  static inline TempDir* dir_ = nullptr;
  static inline std::filesystem::path catalog_;
  static inline ServerProcess* server_ = nullptr;
  static inline auto* ids_ = new std::map<std::string, std::string>();
};

TEST_F(ServerWsTest, StreamsEveryOrderAsGetStreamDoes) {
  for (const std::string name : {"elephant", "holes"}) {
    for (const std::string order : {"quality", "resolution", "rd"}) {
      for (std::optional<uint64_t> budget :
           {std::optional<uint64_t>(2500), std::optional<uint64_t>(6000),
            std::optional<uint64_t>()}) {
        const std::string what =
            name + " " + order + " " +
            (budget ? std::to_string(*budget) : std::string("all"));
        WsTestClient c(port());
        ASSERT_TRUE(c.open()) << c.status();
        const Received r = Exchange(c, StartMessage(Id(name), order, budget));
        ASSERT_TRUE(r.header.has_value()) << what;
        ASSERT_TRUE(r.done.has_value()) << what;
        const HttpReply http = Stream(
            Id(name), "order=" + order +
                          (budget ? "&budget=" + std::to_string(*budget) : ""));
        ASSERT_EQ(http.status, 200u) << what;
        EXPECT_EQ(r.Container(), http.body) << what;
        EXPECT_EQ(r.selection.from_cursor(), 0u);
        EXPECT_EQ(std::to_string(r.selection.next_cursor()),
                  http.Header("x-meshwave-next-cursor"));
        EXPECT_EQ(std::to_string(r.packets.size()),
                  http.Header("x-meshwave-packets"));
        EXPECT_EQ(r.selection.bytes(), http.body.size()) << what;
        EXPECT_EQ(r.done->next_cursor(), r.selection.next_cursor());
        EXPECT_EQ(r.done->complete() ? "true" : "false",
                  http.Header("x-meshwave-complete"));
        EXPECT_EQ(r.done->complete(), !budget.has_value());
      }
    }
  }
}

TEST_F(ServerWsTest, LevelLimitAndHeaderOnly) {
  const std::string& id = Id("elephant");
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  proto::ClientMessage m = StartMessage(id, "resolution");
  m.mutable_start()->set_max_level(1);
  Received r = Exchange(c, m);
  ASSERT_TRUE(r.done.has_value());
  EXPECT_TRUE(r.done->complete());
  EXPECT_EQ(r.Container(), Stream(id, "order=resolution&max_level=1").body);

  // The header alone, then the first packets by Refine on the same socket.
  WsTestClient h(port());
  m = StartMessage(id, "quality");
  m.mutable_start()->set_header_only(true);
  r = Exchange(h, m);
  ASSERT_TRUE(r.header.has_value());
  EXPECT_EQ(*r.header, HttpGet(port(), "/v1/meshes/" + id + "/header").body);
  EXPECT_TRUE(r.packets.empty());
  ASSERT_TRUE(r.done.has_value());
  EXPECT_EQ(r.done->next_cursor(), 0u);
  const Received more = Exchange(h, RefineMessage(3000));
  ASSERT_TRUE(more.done.has_value());
  ASSERT_FALSE(more.packets.empty());
  EXPECT_EQ(more.packets[0].cursor(), 0u);
  EXPECT_LE(more.selection.bytes(), 3000u);
  EXPECT_EQ(more.selection.bytes(), more.Payloads().size());
}

TEST_F(ServerWsTest, PacesToTheRequestedRate) {
  // The whole mesh at the rate that takes about 2.7 s. The first message
  // goes at once and each later one when the bytes before it are paid for,
  // so the rate is the bytes before the last message over the time between
  // first and last (the last, the original layer's finest positions, is a
  // large share: the time is what the bytes before it take).
  const HttpReply container = HttpGet(port(), "/v1/meshes/" + Id("elephant") + "/container");
  ASSERT_EQ(container.status, 200u);
  const double kRate = std::floor(static_cast<double>(container.body.size()) / 2.7);
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  ASSERT_TRUE(c.Send(StartMessage(Id("elephant"), "quality",
                                  std::nullopt, static_cast<uint64_t>(kRate))));
  std::optional<WsTestClient::Clock::time_point> first, last;
  uint64_t bytes = 0, last_size = 0;
  while (auto m = c.Read()) {
    if (m->has_done()) break;
    ASSERT_TRUE(m->has_start() || m->has_packet());
    if (!first) first = c.last_arrival();
    last = c.last_arrival();
    bytes += c.last_size();
    last_size = c.last_size();
  }
  ASSERT_TRUE(first && last);
  const double seconds = std::chrono::duration<double>(*last - *first).count();
  ASSERT_GE(seconds, 1.0) << bytes << " bytes";
  const double rate = static_cast<double>(bytes - last_size) / seconds;
  EXPECT_NEAR(rate, kRate, 0.1 * kRate)
      << bytes << " bytes in " << seconds << " s";
}

TEST_F(ServerWsTest, RefinePullsTheNextPacketsOnTheSameConnection) {
  const std::string& id = Id("elephant");
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  const Received first = Exchange(c, StartMessage(id, "rd", 3000));
  ASSERT_TRUE(first.done.has_value());
  EXPECT_EQ(first.Container(), Stream(id, "order=rd&budget=3000").body);
  uint32_t cursor = first.done->next_cursor();
  for (uint64_t extra : {2000u, 3000u}) {
    const Received more = Exchange(c, RefineMessage(extra));
    ASSERT_TRUE(more.done.has_value());
    EXPECT_FALSE(more.header.has_value());
    EXPECT_EQ(more.selection.from_cursor(), cursor);
    EXPECT_EQ(more.Payloads(),
              Stream(id, "order=rd&from=" + std::to_string(cursor) +
                             "&budget=" + std::to_string(extra))
                  .body);
    cursor = more.done->next_cursor();
  }
  // Past the end: an empty selection, and complete.
  const Received rest = Exchange(c, RefineMessage(uint64_t{1} << 40));
  ASSERT_TRUE(rest.done.has_value());
  EXPECT_TRUE(rest.done->complete());
  const Received none = Exchange(c, RefineMessage(1000));
  ASSERT_TRUE(none.done.has_value());
  EXPECT_TRUE(none.packets.empty());
  EXPECT_TRUE(none.done->complete());
}

TEST_F(ServerWsTest, ARefineDuringAStreamGetsItsOwnDone) {
  const std::string& id = Id("elephant");
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  // Paced (about 0.3 s) so that the refine arrives while the start streams.
  ASSERT_TRUE(c.Send(StartMessage(id, "resolution", 6000, 20000)));
  ASSERT_TRUE(c.Send(RefineMessage(2000)));
  ASSERT_TRUE(c.Send(RefineMessage(1)));  // selects nothing: still a Done
  std::vector<proto::ServerMessage> messages;
  std::vector<proto::Done> dones;
  while (dones.size() < 3) {
    auto m = c.Read();
    ASSERT_TRUE(m.has_value()) << c.error().message();
    messages.push_back(*m);
    if (m->has_done()) dones.push_back(m->done());
  }
  const HttpReply first = Stream(id, "order=resolution&budget=6000");
  const uint32_t end1 = std::stoul(first.Header("x-meshwave-next-cursor"));
  const HttpReply second =
      Stream(id, "order=resolution&from=" + std::to_string(end1) + "&budget=2000");
  const uint32_t end2 = std::stoul(second.Header("x-meshwave-next-cursor"));
  ASSERT_GT(end2, end1);
  EXPECT_EQ(dones[0].next_cursor(), end1);
  EXPECT_EQ(dones[1].next_cursor(), end2);
  EXPECT_EQ(dones[2].next_cursor(), end2);
  // Each Done follows the last packet of its request, and the packets are
  // those of /stream then /stream?from=.
  std::string payloads;
  uint32_t last_cursor = 0;
  for (const auto& m : messages) {
    if (m.has_packet()) {
      payloads += m.packet().payload();
      last_cursor = m.packet().cursor() + 1;
    }
    if (m.has_done()) {
      EXPECT_EQ(m.done().next_cursor(), last_cursor);
    }
  }
  ASSERT_TRUE(messages.front().has_start());
  const auto parsed = ParseContainer(first.body);
  ASSERT_TRUE(parsed.ok());
  std::string expected;
  for (const auto& p : parsed->payloads) expected += p;
  EXPECT_EQ(payloads, expected + second.body);
  // Nothing more comes: exactly one Done per request.
  EXPECT_FALSE(c.Read(std::chrono::milliseconds(300)).has_value());
}

TEST_F(ServerWsTest, ResumeContinuesAfterAReconnect) {
  const std::string& id = Id("holes");
  uint32_t held = 0;
  {
    WsTestClient c(port());
    ASSERT_TRUE(c.open());
    ASSERT_TRUE(c.Send(StartMessage(id, "quality", 8000)));
    // Take the header and three packets, then drop the connection.
    while (auto m = c.Read()) {
      if (m->has_packet() && ++held == 3) break;
    }
    ASSERT_EQ(held, 3u);
  }
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  const Received r = Exchange(c, ResumeMessage(id, "quality", held, 4000));
  ASSERT_TRUE(r.done.has_value());
  EXPECT_FALSE(r.header.has_value());
  EXPECT_EQ(r.selection.from_cursor(), held);
  EXPECT_EQ(r.Payloads(), Stream(id, "order=quality&from=3&budget=4000").body);
  // Refine continues the resumed stream.
  const Received more = Exchange(c, RefineMessage(2000));
  EXPECT_EQ(
      more.Payloads(),
      Stream(id, "order=quality&from=" + std::to_string(r.done->next_cursor()) +
                     "&budget=2000")
          .body);
}

// docs/API.md, "Re-encoded meshes": the start names the container served;
// a resume naming it continues, one naming another gets CONFLICT naming
// both, and the connection stays usable.
TEST_F(ServerWsTest, AResumeNamesItsContainer) {
  const std::string& id = Id("holes");
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  std::string digest;
  ASSERT_TRUE(c.Send(StartMessage(id, "quality", 6000)));
  for (const auto& m : c.ReadUntilDone()) {
    if (m.has_start()) digest = m.start().container();
  }
  EXPECT_EQ(digest, HttpGet(port(), "/v1/meshes/" + id + "/header").Header("x-meshwave-container"));
  ASSERT_EQ(digest.size(), 64u);

  proto::ClientMessage resume = ResumeMessage(id, "quality", 3, 4000);
  resume.mutable_resume()->set_container(digest);
  Received r = Exchange(c, resume);
  ASSERT_FALSE(r.error.has_value()) << r.error->message();
  EXPECT_EQ(r.Payloads(), Stream(id, "order=quality&from=3&budget=4000").body);

  const std::string other(64, '0');
  resume.mutable_resume()->set_container(other);
  ASSERT_TRUE(c.Send(resume));
  auto refused = c.Read();
  ASSERT_TRUE(refused && refused->has_error());
  EXPECT_EQ(refused->error().code(), proto::Error::CONFLICT);
  EXPECT_NE(refused->error().message().find(digest), std::string::npos) << refused->error().message();
  EXPECT_NE(refused->error().message().find(other), std::string::npos);

  resume.mutable_resume()->set_container("not a digest");
  ASSERT_TRUE(c.Send(resume));
  refused = c.Read();
  ASSERT_TRUE(refused && refused->has_error());
  EXPECT_EQ(refused->error().code(), proto::Error::BAD_REQUEST);

  proto::ClientMessage start = StartMessage(id, "quality", 3000);
  start.mutable_start()->set_container(digest);
  r = Exchange(c, start);
  EXPECT_TRUE(r.done.has_value());
  EXPECT_FALSE(r.error.has_value());
}

TEST_F(ServerWsTest, BadRequestsGetErrorsAndTheConnectionStaysUsable) {
  const std::string& id = Id("holes");
  WsTestClient c(port());
  ASSERT_TRUE(c.open());
  auto expect_error = [&](const proto::ClientMessage& m,
                          proto::Error::Code code, const std::string& text) {
    const Received r = Exchange(c, m);
    ASSERT_TRUE(r.error.has_value()) << text;
    EXPECT_EQ(r.error->code(), code) << r.error->message();
    EXPECT_NE(r.error->message().find(text), std::string::npos)
        << r.error->message();
  };
  expect_error(RefineMessage(100), proto::Error::BAD_REQUEST,
               "nothing to refine");
  expect_error(StartMessage("0123456789ab", "quality"), proto::Error::NOT_FOUND,
               "no mesh");
  expect_error(StartMessage("../../x", "quality"), proto::Error::BAD_REQUEST,
               "invalid mesh id");
  expect_error(StartMessage(id, "best"), proto::Error::BAD_REQUEST,
               "unknown order");
  expect_error(StartMessage(id, "quality", 10), proto::Error::BAD_REQUEST,
               "smaller than the stream header");
  proto::ClientMessage m = StartMessage(id, "quality");
  m.mutable_start()->set_max_level(9);
  expect_error(m, proto::Error::BAD_REQUEST, "exceeds the 2 levels");
  expect_error(ResumeMessage(id, "quality", 9999, 100),
               proto::Error::BAD_REQUEST, "past the end of the order");
  ASSERT_TRUE(c.SendRaw("\xff\x01garbage"));
  const auto garbage = c.Read();
  ASSERT_TRUE(garbage && garbage->has_error());
  EXPECT_EQ(garbage->error().code(), proto::Error::BAD_REQUEST);
  // Invalid UTF-8 in the id or the order: refused like any bad value, and
  // no protobuf log line per message (the fields are `bytes`).
  for (int i = 0; i < 5; ++i) {
    expect_error(StartMessage("\xff\xfe\xc0\x80", "quality"), proto::Error::BAD_REQUEST,
                 "invalid mesh id");
    expect_error(StartMessage(id, "qu\xff"
                                   "ality"), proto::Error::BAD_REQUEST, "unknown order");
  }
  EXPECT_EQ(ReadBytes(server_->log()).find("UTF-8"), std::string::npos);

  // Still open: a good request works, and a second start while it streams
  // is refused without disturbing it.
  // (The refusal, a small message, may come before, among or after the
  // stream's packets.)
  // Paced to last about 0.3 s, so that the second start finds it running.
  ASSERT_TRUE(c.Send(StartMessage(id, "quality", 6000, 20000)));
  ASSERT_TRUE(c.Send(StartMessage(id, "rd")));
  std::vector<proto::ServerMessage> messages;
  bool done = false, refused = false;
  while (!(done && refused)) {
    auto next = c.Read();
    ASSERT_TRUE(next.has_value()) << c.error().message();
    messages.push_back(*next);
    done = done || next->has_done();
    refused = refused || next->has_error();
  }
  const Received r = Collect(messages);
  ASSERT_TRUE(r.done.has_value());
  EXPECT_EQ(r.Container(), Stream(id, "order=quality&budget=6000").body);
  ASSERT_TRUE(r.error.has_value());
  EXPECT_NE(r.error->message().find("in progress"), std::string::npos);
}

TEST_F(ServerWsTest, OversizeAndTextMessagesCloseTheConnection) {
  {
    WsTestClient c(port());
    ASSERT_TRUE(c.open());
    ASSERT_TRUE(c.SendRaw(std::string(70 * 1024, 'x')));  // the limit is 64 KiB
    EXPECT_FALSE(c.Read().has_value());
    // Beast closes the socket right after its close frame, so answering it
    // may fail (broken pipe): the code received is what counts.
    EXPECT_EQ(c.close_reason().code, websocket::close_code::too_big)
        << c.error().message();
  }
  {
    WsTestClient c(port());
    ASSERT_TRUE(c.open());
    ASSERT_TRUE(c.SendRaw("{\"start\": {}}", /*binary=*/false));
    EXPECT_FALSE(c.Read().has_value());
    EXPECT_EQ(c.close_reason().code, websocket::close_code::unknown_data)
        << c.error().message();
  }
  EXPECT_EQ(HttpGet(port(), "/healthz").status, 200u);
}

TEST_F(ServerWsTest, UpgradeRefusalsAreHttpErrors) {
  WsTestClient wrong_path(port(), "/v1/meshes");
  EXPECT_FALSE(wrong_path.open());
  EXPECT_EQ(wrong_path.status(), 404u);
  WsTestClient query(port(), "/v1/ws?x=1");
  EXPECT_FALSE(query.open());
  EXPECT_EQ(query.status(), 400u);
  // Path rules: only /v1/ws; a trailing '/' or a malformed path is another
  // path (404), any query 400.
  for (const char* target : {"/v1/ws/", "/v1//ws", "/v1/ws/..", "/v1/ws%2f"}) {
    WsTestClient other(port(), target);
    EXPECT_FALSE(other.open()) << target;
    EXPECT_EQ(other.status(), 404u) << target;
  }
  WsTestClient bad_query(port(), "/v1/ws?%zz");
  EXPECT_EQ(bad_query.status(), 400u);
  EXPECT_EQ(HttpGet(port(), "/v1/ws").status, 426u);  // no upgrade

  auto limited = StartServer("limited", "max_websocket_sessions: 2\n");
  ASSERT_TRUE(limited->running()) << ReadBytes(limited->log());
  WsTestClient a(limited->port()), b(limited->port());
  ASSERT_TRUE(a.open());
  ASSERT_TRUE(b.open());
  WsTestClient over(limited->port());
  EXPECT_FALSE(over.open());
  EXPECT_EQ(over.status(), 503u);
  const HttpReply metrics = HttpGet(limited->port(), "/metrics");
  EXPECT_NE(metrics.body.find("meshwave_websocket_connections 2\n"),
            std::string::npos)
      << metrics.body;
  a.Close();
  b.Close();
  // The gauge follows the sessions down.
  std::string body;
  for (int i = 0; i < 100; ++i) {
    body = HttpGet(limited->port(), "/metrics").body;
    if (body.find("meshwave_websocket_connections 0\n") != std::string::npos)
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_NE(body.find("meshwave_websocket_connections 0\n"), std::string::npos)
      << body;
  WsTestClient again(limited->port());
  EXPECT_TRUE(again.open());
}

TEST_F(ServerWsTest, HandshakeRefusalsAreJsonErrors) {
  const std::vector<std::pair<std::string, std::string>> upgrade = {
      {"Connection", "Upgrade"},
      {"Upgrade", "websocket"},
      {"Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="}};
  const auto with = [&](std::vector<std::pair<std::string, std::string>> extra) {
    auto h = upgrade;
    h.insert(h.end(), extra.begin(), extra.end());
    return h;
  };
  const auto is_json_error = [](const HttpReply& r) {
    return r.Header("content-type") == "application/json" &&
           r.body.starts_with("{\"error\": \"") && r.Header("cache-control") == "no-store";
  };
  // Refused by Beast's handshake checks (no longer its plain text).
  HttpReply r = HttpGet(port(), "/v1/ws", with({{"Sec-WebSocket-Version", "12"}}));
  EXPECT_EQ(r.status, 426u);
  EXPECT_EQ(r.Header("sec-websocket-version"), "13");
  EXPECT_TRUE(is_json_error(r)) << r.body;
  EXPECT_NE(r.body.find("WebSocket handshake refused"), std::string::npos) << r.body;
  r = HttpGet(port(), "/v1/ws", {{"Connection", "Upgrade"}, {"Upgrade", "websocket"},
                                 {"Sec-WebSocket-Version", "13"}});  // no key
  EXPECT_EQ(r.status, 400u);
  EXPECT_TRUE(is_json_error(r)) << r.body;
  // Refused by the server's own checks.
  for (const char* target : {"/v1/ws/", "/v1/ws?x=1"}) {
    r = HttpGet(port(), target, with({{"Sec-WebSocket-Version", "13"}}));
    EXPECT_TRUE(is_json_error(r)) << target << ": " << r.body;
  }
  EXPECT_EQ(HttpGet(port(), "/healthz").status, 200u);
}

TEST_F(ServerWsTest, KeepAlivePingsHoldAnAnsweringClientAndDropASilentOne) {
  // Pings after 1 s without a frame from the client, closes after 2 s.
  auto server = StartServer("pings", "websocket_ping_seconds: 1\n");
  ASSERT_TRUE(server->running()) << ReadBytes(server->log());
  WsTestClient answering(server->port()), silent(server->port());
  ASSERT_TRUE(answering.open());
  ASSERT_TRUE(silent.open());
  // Reading, Beast answers each ping with a pong: the session stays.
  EXPECT_TRUE(answering.IdleFor(std::chrono::milliseconds(4500)));
  EXPECT_GE(answering.pings(), 2);
  const Received r =
      Exchange(answering, StartMessage(Id("holes"), "quality", 4000));
  ASSERT_TRUE(r.done.has_value());
  EXPECT_EQ(r.Container(),
            Stream(Id("holes"), "order=quality&budget=4000").body);
  // The silent one never read, so never answered: the server closed it
  // with a close frame (1008) that waits in its socket. (The server has
  // dropped the socket a second after that unanswered close, so answering
  // it now may fail with a broken pipe: the code received is what counts.)
  EXPECT_FALSE(silent.Read(std::chrono::milliseconds(2000)).has_value());
  EXPECT_NE(silent.error(), beast::error::timeout) << silent.error().message();
  EXPECT_EQ(silent.close_reason().code, websocket::close_code::policy_error);
  const auto& reason = silent.close_reason().reason;
  EXPECT_EQ(std::string(reason.data(), reason.size()), "keep-alive pings unanswered");
  EXPECT_NE(ReadBytes(server->log()).find("no answer to keep-alive pings"), std::string::npos);
}

TEST_F(ServerWsTest, AClientThatNeverAnswersTheCloseLosesTheSocket) {
  // The close frame goes; without an answer within a ping period the
  // connection is dropped anyway (the session count falls to 0).
  auto server = StartServer("close_unanswered", "websocket_ping_seconds: 1\n");
  ASSERT_TRUE(server->running()) << ReadBytes(server->log());
  WsTestClient silent(server->port());
  ASSERT_TRUE(silent.open());
  std::string body;
  for (int i = 0; i < 100; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    body = HttpGet(server->port(), "/metrics").body;
    if (body.find("meshwave_websocket_connections 0\n") != std::string::npos) break;
  }
  EXPECT_NE(body.find("meshwave_websocket_connections 0\n"), std::string::npos) << body;
}

TEST_F(ServerWsTest, ShutdownClosesSessionsWithGoingAway) {
  auto server = StartServer("shutdown", "");
  ASSERT_TRUE(server->running());
  WsTestClient c(server->port());
  ASSERT_TRUE(c.open());
  // A slow stream in progress when SIGTERM arrives.
  ASSERT_TRUE(c.Send(
      StartMessage(Id("elephant"), "quality", std::nullopt, 5000)));
  ASSERT_TRUE(c.Read().has_value());
  std::thread stop(
      [&] { EXPECT_EQ(server->Stop(), 0) << ReadBytes(server->log()); });
  while (c.Read(std::chrono::seconds(10))) {
  }
  stop.join();
  EXPECT_EQ(c.error(), websocket::error::closed) << c.error().message();
  EXPECT_EQ(c.close_reason().code, websocket::close_code::going_away);
}

}  // namespace
}  // namespace meshwave::testing
