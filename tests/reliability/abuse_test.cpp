// Abuse tests (docs/RELIABILITY.md): slowloris, header and body floods,
// request-rate floods, path traversal and encoded-id tricks, uploads
// without or with a wrong token, and meshes claiming huge counts. Each is
// bounded in time, loopback only, and checks that the server answers
// others throughout and returns to its resting memory and descriptors.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "reliability_testonly.h"

namespace meshwave::testing {
namespace {

class AbuseTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new TempDir();
    std::filesystem::create_directories(*tmp_ / "work");
    ASSERT_NO_FATAL_FAILURE(CopySampleCatalog(*tmp_ / "catalog", {SampleMesh("holes.off")}));
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  void Start(const std::string& config) {
    server_ = StartServer(*tmp_ / "catalog", *tmp_ / "work", config);
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    port_ = server_->port();
    const HttpReply list = HttpGet(port_, "/v1/meshes");
    const size_t at = list.body.find("\"id\": \"");
    ASSERT_NE(at, std::string::npos) << list.body;
    id_ = list.body.substr(at + 7, 12);
  }
  void TearDown() override {
    if (server_) {
      EXPECT_TRUE(Alive(server_->pid())) << "the server died: " << ReadBytes(server_->log());
      EXPECT_EQ(server_->Stop(), 0);
    }
  }
  // A request from a well-behaved client: answered 200 within `within`.
  void ExpectServed(const char* during, std::chrono::milliseconds within = std::chrono::seconds(2)) {
    const auto start = std::chrono::steady_clock::now();
    const HttpReply r = HttpGet(port_, "/v1/meshes/" + id_ + "/stream?budget=5000");
    const auto took = std::chrono::steady_clock::now() - start;
    EXPECT_EQ(r.status, 200u) << during;
    EXPECT_LT(took, within) << during;
  }

  static TempDir* tmp_;
  std::unique_ptr<ServerProcess> server_;
  uint16_t port_ = 0;
  std::string id_;
};
TempDir* AbuseTest::tmp_ = nullptr;

// Many connections trickle a request header a byte at a time: each is
// closed header_timeout_seconds after its first byte, others are served
// meanwhile, and the server's descriptors return to their resting count.
TEST_F(AbuseTest, SlowlorisConnectionsAreClosedAndOthersServed) {
  Start("header_timeout_seconds: 2\nidle_timeout_seconds: 30\n");
  const long fds_before = FdCount(server_->pid());
  constexpr int kSlow = 200;
  std::vector<std::unique_ptr<RawSocket>> slow;
  for (int i = 0; i < kSlow; ++i) {
    slow.push_back(std::make_unique<RawSocket>(port_));
    ASSERT_TRUE(slow.back()->connected());
    slow.back()->Write("GET /v1/meshes HTTP/1.1\r\n");
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<bool> closed(kSlow, false);
  int closed_count = 0;
  // Keep trickling ("X-a: a" one byte every 250 ms) for up to 6 s.
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(6) && closed_count < kSlow) {
    for (int i = 0; i < kSlow; ++i) {
      if (closed[i]) continue;
      if (!slow[i]->Write("a") || slow[i]->ClosedByPeer()) {
        closed[i] = true;
        ++closed_count;
      }
    }
    ExpectServed("slowloris");
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(closed_count, kSlow) << "half-open requests still open after " << took << " s";
  EXPECT_GE(took, 1.5);  // not before the timeout
  std::cout << kSlow << " slowloris connections closed after " << took << " s\n";
  slow.clear();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_LE(FdCount(server_->pid()), fds_before + 2);
}

// Keep-alive connections: one that asks again within idle_timeout_seconds
// stays open however long it lasts (the deadline moves with each request),
// one that stays silent is closed once the idle timeout has passed.
TEST_F(AbuseTest, IdleKeepAliveConnectionsAreClosedAfterTheIdleTimeout) {
  Start("idle_timeout_seconds: 1\n");
  RawSocket idle(port_);
  ASSERT_TRUE(idle.Write("GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n"));
  HttpConnection busy(port_);
  const auto start = std::chrono::steady_clock::now();
  double idle_closed_after = -1;
  while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(3000)) {
    ASSERT_EQ(busy.Send(http::verb::get, "/v1/meshes/" + id_ + "/packets/0").status, 200u);
    if (idle_closed_after < 0 && idle.ClosedByPeer()) {
      idle_closed_after =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_GE(idle_closed_after, 0.8) << "closed before its idle timeout";
  EXPECT_LE(idle_closed_after, 2.5) << "still open well past its idle timeout";
  std::cout << "silent keep-alive connection closed after " << idle_closed_after << " s\n";
  EXPECT_EQ(busy.Send(http::verb::get, "/healthz").status, 200u);  // 3 s, still open
}

// A client that stops reading a large response: the write gets
// write_timeout_seconds, then the connection is dropped and others are
// served throughout.
TEST_F(AbuseTest, AClientThatStopsReadingIsDroppedAfterTheWriteTimeout) {
  Start("write_timeout_seconds: 1\n");
  auto connections = [&] {
    const std::string body = HttpGet(port_, "/metrics").body;
    const std::string key = "\nmeshwave_http_connections ";
    const size_t at = body.find(key);
    return at == std::string::npos ? -1L : std::stol(body.substr(at + key.size()));
  };
  RawSocket stalled(port_);
  stalled.socket().set_option(net::socket_base::receive_buffer_size(4096));
  // Pipelined requests for the whole container, never read: the server's
  // writes fill the socket buffers and wait.
  std::string requests;
  for (int i = 0; i < 2000; ++i) {
    requests += "GET /v1/meshes/" + id_ + "/container HTTP/1.1\r\nHost: x\r\n\r\n";
  }
  const auto start = std::chrono::steady_clock::now();
  stalled.Write(requests);
  long open = -1;
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
    ExpectServed("a stalled reader");
    open = connections();  // the stalled one and this request's own
    if (open == 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(open, 1) << "the stalled connection is still open after " << took << " s";
  EXPECT_GE(took, 0.8);
  std::cout << "stalled reader dropped after " << took << " s\n";
}

// Headers past the limit get 431, bodies past the limit 413 (announced or
// chunked), without the server reading them in full; it keeps serving.
TEST_F(AbuseTest, HeaderAndBodyFloodsAreRefused) {
  Start("header_limit_bytes: 8192\nbody_limit_bytes: 65536\n");
  const long rss_before = RssKib(server_->pid());
  {
    RawSocket s(port_);
    std::string req = "GET /v1/meshes HTTP/1.1\r\nHost: x\r\n";
    for (int i = 0; i < 2000; ++i) req += Numbered("X-Flood-", i) + ": " + std::string(40, 'f') + "\r\n";
    req += "\r\n";
    s.Write(req);
    EXPECT_NE(s.ReadAll().find("HTTP/1.1 431"), std::string::npos);
  }
  {
    RawSocket s(port_);
    s.Write("GET /" + std::string(100000, 'a') + " HTTP/1.1\r\n\r\n");
    const std::string r = s.ReadAll();
    EXPECT_TRUE(r.find("HTTP/1.1 431") != std::string::npos || r.find("HTTP/1.1 400") != std::string::npos) << r.substr(0, 100);
  }
  {
    RawSocket s(port_);
    s.Write("GET /v1/meshes HTTP/1.1\r\nContent-Length: 1000000000\r\n\r\n");
    EXPECT_NE(s.ReadAll().find("HTTP/1.1 413"), std::string::npos);
  }
  {
    // Chunked: the limit applies as the chunks arrive.
    RawSocket s(port_);
    s.Write("GET /v1/meshes HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n");
    const std::string chunk = "10000\r\n" + std::string(0x10000, 'c') + "\r\n";
    std::string r;
    for (int i = 0; i < 64 && s.Write(chunk); ++i) {
    }
    r = s.ReadAll();
    EXPECT_NE(r.find("HTTP/1.1 413"), std::string::npos) << r.substr(0, 100);
  }
  ExpectServed("after floods");
  EXPECT_LT(RssKib(server_->pid()), rss_before + 64 * 1024) << "memory grew by the floods";
}

// One client floods requests: past rate + burst it gets 429 with
// Retry-After, while another client (another address) is served.
TEST_F(AbuseTest, RequestRateFloodFromOneClientIsLimited) {
  Start("rate_limit_requests_per_second: 50\nrate_limit_burst: 20\n");
  const auto start = std::chrono::steady_clock::now();
  int ok = 0, limited = 0, other = 0;
  for (int i = 0; i < 400; ++i) {
    HttpConnection c(port_);
    const HttpReply r = c.Send(http::verb::get, "/healthz");
    if (r.status == 200) ++ok;
    else if (r.status == 429) {
      ++limited;
      EXPECT_EQ(r.Header("retry-after"), "1");
    } else ++other;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(other, 0);
  EXPECT_GT(limited, 0);
  EXPECT_LE(ok, 20 + static_cast<int>(50 * seconds) + 5) << seconds << " s";
  std::cout << "flood: " << ok << " served, " << limited << " refused with 429 in " << seconds << " s\n";
  // Another client is not affected.
  RawSocket s(port_, "127.0.0.2");
  ASSERT_TRUE(s.connected());
  s.Write("GET /healthz HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_NE(s.ReadAll().find("HTTP/1.1 200"), std::string::npos);
}

// Traversal and encoded-id tricks never reach a file: 400 or 404, with a
// JSON error, never 200 or 5xx. (A percent-encoded valid id is the same
// URI and is served the same bytes.)
TEST_F(AbuseTest, PathTraversalAndEncodedIdsAreRefused) {
  Start("");
  std::string upper = id_;
  for (auto& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  std::string encoded;
  for (char c : id_) {
    char hex[4];
    std::snprintf(hex, sizeof hex, "%%%02x", static_cast<unsigned char>(c));
    encoded += hex;
  }
  const std::vector<std::string> targets = {
      "/../catalog.db", "/v1/meshes/../../catalog.db", "/v1/meshes/%2e%2e/%2e%2e/catalog.db",
      "/v1/meshes/%2E%2E%2Fcatalog.db", "/v1/meshes/..%2fcatalog.db", "/v1/meshes/..%5ccatalog.db",
      "/v1/meshes/" + id_ + "/..", "/v1/meshes/" + id_ + "/%2e%2e/container",
      "/v1/meshes/" + upper + "/container",
      "/v1/meshes/" + id_ + "%00/container", "/v1/meshes/" + id_ + "0/container",
      "/v1/meshes/" + id_.substr(0, 11) + "/container", "/v1/meshes/%c0%ae%c0%ae/container",
      "/v1/meshes/" + id_ + "/packets/-1", "/v1/meshes/" + id_ + "/packets/99999999999999999999",
      "/v1/meshes/" + id_ + "/packets/0x1", "/v1/meshes/" + id_ + "/containers/" + id_,
      "//v1/meshes", "/v1//meshes", "/v1/meshes/./" + id_, "/containers/", "/v1/meshes/" + id_ + "#x",
      "/v1/meshes/" + id_ + "/stream?budget=1&budget=2", "/v1/meshes/" + id_ + "/stream?from=-1",
      "/v1/meshes/" + id_ + "/stream?max_level=1e3", "http://evil/v1/meshes", "*"};
  for (const auto& t : targets) {
    RawSocket s(port_);
    s.Write("GET " + t + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    const std::string r = s.ReadAll();
    const bool refused = r.starts_with("HTTP/1.1 400") || r.starts_with("HTTP/1.1 404");
    EXPECT_TRUE(refused) << t << " -> " << r.substr(0, r.find("\r\n"));
    EXPECT_EQ(r.find("SQLite format"), std::string::npos) << t;
    EXPECT_EQ(r.find("MWV1"), std::string::npos) << t;
  }
  // The id with every character percent-encoded is the same URI (RFC 3986
  // 6.2.2.2: unreserved characters decode to themselves) and is the same
  // mesh: served the same bytes, not refused and not anything else.
  const HttpReply plain = HttpGet(port_, "/v1/meshes/" + id_ + "/container");
  const HttpReply same = HttpGet(port_, "/v1/meshes/" + encoded + "/container");
  EXPECT_EQ(plain.status, 200u);
  EXPECT_EQ(same.status, 200u);
  EXPECT_EQ(same.body, plain.body);
  ExpectServed("after traversal attempts");
}

// Uploads and deletions without a bearer token (none, or Basic) get 401,
// with a wrong one 403, before the body is read (a 50 MB body is not
// waited for); nothing is ingested or deleted.
TEST_F(AbuseTest, UploadsWithoutOrWithAWrongTokenAreRefusedUnread) {
  Start("");
  const std::vector<std::pair<std::string, const char*>> cases = {
      {"", "HTTP/1.1 401"},
      {"Authorization: Basic eDp5\r\n", "HTTP/1.1 401"},
      {"Authorization: Bearer wrong\r\n", "HTTP/1.1 403"},
      {std::string("Authorization: Bearer ") + kToken + "x\r\n", "HTTP/1.1 403"}};
  for (const auto& [auth, expected] : cases) {
    RawSocket s(port_);
    const auto start = std::chrono::steady_clock::now();
    s.Write("POST /v1/meshes?format=off HTTP/1.1\r\nHost: x\r\n" + auth +
            "Content-Length: 50000000\r\n\r\nOFF\n");
    const std::string r = s.ReadAll();
    EXPECT_TRUE(r.starts_with(expected)) << auth << r.substr(0, 40);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
    RawSocket d(port_);
    d.Write("DELETE /v1/meshes/" + id_ + " HTTP/1.1\r\n" + auth + "Connection: close\r\n\r\n");
    const std::string dr = d.ReadAll();
    EXPECT_TRUE(dr.starts_with(expected)) << auth << dr.substr(0, 40);
  }
  const HttpReply list = HttpGet(port_, "/v1/meshes");
  EXPECT_NE(list.body.find(id_), std::string::npos);
  EXPECT_EQ(list.body.find("\"name\": \"off\""), std::string::npos);
}

// Meshes that claim huge counts in a few bytes (a decompression bomb's
// shape) are refused with 422 quickly, without the server's memory growing.
TEST_F(AbuseTest, MeshesClaimingHugeCountsAreRefusedCheaply) {
  Start("");
  const long rss_before = RssKib(server_->pid());
  std::string binary_ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4294967295\nproperty float x\n"
      "property float y\nproperty float z\nelement face 4294967295\n"
      "property list uchar int vertex_indices\nend_header\n";
  binary_ply += std::string(64, '\0');
  std::string face_list = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                          "property float y\nproperty float z\nelement face 1\n"
                          "property list uint int vertex_indices\nend_header\n" + std::string(36, '\0');
  face_list += std::string("\xff\xff\xff\xff", 4);  // a face of 4 billion corners
  const std::vector<std::pair<std::string, std::string>> bombs = {
      {"off", "OFF\n4000000000 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n"},
      {"ply", binary_ply},
      {"ply", face_list},
      {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n"},
      {"obj", "v 0 0 0\nv 1e308 1e308 1e308\nv -1e308 0 1\nf 1 2 3\n"},
  };
  for (const auto& [format, body] : bombs) {
    const auto start = std::chrono::steady_clock::now();
    HttpConnection c(port_);
    const HttpReply r = c.Send(http::verb::post, "/v1/meshes?format=" + format,
                               {{"Authorization", std::string("Bearer ") + kToken}}, body);
    EXPECT_EQ(r.status, 422u) << body.substr(0, 60) << " -> " << r.body;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10)) << body.substr(0, 40);
  }
  EXPECT_LT(RssKib(server_->pid()), rss_before + 128 * 1024) << "memory grew by the bombs";
  ExpectServed("after bombs");
}

}  // namespace
}  // namespace meshwave::testing
