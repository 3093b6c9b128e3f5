// The scaled-out deployment on loopback, from Debian's packages: one
// PostgreSQL catalog, two meshwave-server replicas sharing a container
// store, nginx in front as load balancer and cache with the shipped
// deploy/nginx/meshwave-locations.conf. An upload through one replica is
// served by the other; a fetch through nginx survives the replica serving
// it being killed mid-stream; the same fetch again, with every replica
// stopped, is served from nginx's cache (X-Cache-Status: HIT), Range and
// ETag included.
#include <gtest/gtest.h>
#include <signal.h>

#include <google/protobuf/util/json_util.h>

#include <memory>
#include <regex>
#include <thread>

#include "catalog_api.pb.h"
#include "client/tcp_proxy_testonly.h"
#include "client_state.pb.h"
#include "deploy/nginx_process_testonly.h"
#include "e2e/cli_runner.h"
#include "server/http_client_testonly.h"
#include "server/postgres_instance_testonly.h"
#include "server/server_process_testonly.h"

namespace meshwave {
namespace {

using testing::HttpConnection;
using testing::HttpGet;
using testing::NginxProcess;
using testing::PostgresInstance;
using testing::ReadBytes;
using testing::RunCli;
using testing::ServerProcess;
using testing::TcpProxy;
using testing::TempDir;
namespace http = boost::beast::http;

constexpr char kToken[] = "replica-test-token";

proto::FetchReport ParseReport(const std::string& json) {
  proto::FetchReport r;
  google::protobuf::util::JsonParseOptions o;
  o.ignore_unknown_fields = true;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &r, o).ok()) << json;
  return r;
}

// The values of every X-Cache-Status header in a transcript of responses.
std::vector<std::string> CacheStatuses(const std::string& transcript) {
  std::vector<std::string> out;
  static const std::regex kHeader("\r\nX-Cache-Status: ([A-Z]*)\r\n", std::regex::icase);
  for (std::sregex_iterator it(transcript.begin(), transcript.end(), kHeader), end; it != end;
       ++it) {
    out.push_back((*it)[1]);
  }
  return out;
}

class ReplicasE2eTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const auto& why : {testing::PostgresUnavailableReason(),
                            std::string(testing::NginxBinary().empty()
                                            ? "nginx not found (apt-get install nginx-light)"
                                            : "")}) {
      if (why.empty()) continue;
      if (std::getenv("CI") != nullptr) GTEST_FAIL() << why << " (CI must run this test)";
      GTEST_SKIP() << why;
    }
    pg_ = std::make_unique<PostgresInstance>();
    ASSERT_TRUE(pg_->ok()) << pg_->error();
    for (const char* d : {"a", "b"}) std::filesystem::create_directories(tmp_ / d);
  }

  std::unique_ptr<ServerProcess> StartReplica(const std::string& name) {
    // Same catalog, same store: what compose and the Deployment give every
    // replica (MESHWAVE_CATALOG, MESHWAVE_STORE).
    auto replica = std::make_unique<ServerProcess>(
        pg_->Uri(), tmp_ / name,
        std::vector<std::string>{std::string("MESHWAVE_UPLOAD_TOKEN=") + kToken},
        std::vector<std::string>{"--store", (tmp_ / "store").string()});
    EXPECT_TRUE(replica->running()) << ReadBytes(replica->log());
    return replica;
  }

  TempDir tmp_;
  std::unique_ptr<PostgresInstance> pg_;
};

TEST_F(ReplicasE2eTest, IngestOnOneReplicaFetchThroughNginxSurvivesAKillAndIsCached) {
  auto a = StartReplica("a");
  auto b = StartReplica("b");
  ASSERT_TRUE(a->running() && b->running());

  // --- ingest through replica a, visible on replica b ----------------------
  HttpConnection upload(a->port());
  const auto created = upload.Send(
      http::verb::post, "/v1/meshes?name=elephant&format=off",
      {{"Authorization", std::string("Bearer ") + kToken}},
      ReadBytes(testing::SampleMesh("elephant.off")));
  ASSERT_EQ(created.status, 201u) << created.body;
  const std::string location = created.Header("location");
  ASSERT_TRUE(location.starts_with("/v1/meshes/")) << location;
  const std::string id = location.substr(std::string("/v1/meshes/").size());
  const auto on_b = HttpGet(b->port(), "/v1/meshes/" + id);
  EXPECT_EQ(on_b.status, 200u) << on_b.body;
  const auto listed = HttpGet(b->port(), "/v1/meshes");
  EXPECT_NE(listed.body.find(id), std::string::npos) << listed.body;
  // What a complete fetch must decode to: the whole rd stream, from b.
  const auto whole = HttpGet(b->port(), "/v1/meshes/" + id + "/stream?order=rd");
  ASSERT_EQ(whole.status, 200u);
  std::ofstream(tmp_ / "whole.mwv", std::ios::binary) << whole.body;
  auto r = RunCli({"decode", (tmp_ / "whole.mwv").string(), (tmp_ / "expected.ply").string(),
                   "--order", "rd"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string expected = ReadBytes(tmp_ / "expected.ply");

  // --- nginx in front; replica a behind a proxy that holds its response ---
  // The proxy only fixes the moment of the kill: it forwards a's bytes
  // until 5000 have gone to nginx, then waits while a is killed.
  TcpProxy hold_a(a->port());
  hold_a.StallAfter(5000);
  NginxProcess nginx({hold_a.port(), b->port()},
                     testing::SourceDir() /
                         "deploy/nginx/meshwave-locations.conf");
  ASSERT_TRUE(nginx.ok()) << nginx.error();
  TcpProxy client_side(nginx.port());  // records nginx's responses
  const std::string url =
      "http://127.0.0.1:" + std::to_string(client_side.port()) + "/v1/meshes/" + id;

  // --- fetch 1: replica a is killed mid-stream ----------------------------
  testing::CliResult first;
  std::thread fetch([&] {
    first = RunCli({"fetch", url, "--order", "rd", "--out", (tmp_ / "first.ply").string(),
                    "--json", "--retry-delay", "50ms"});
  });
  if (!hold_a.WaitStalled(std::chrono::seconds(30))) {
    hold_a.DropStalled();
    fetch.join();
    FAIL() << "nginx never sent the stream to replica a: " << first.err << nginx.AccessLog();
  }
  ::kill(a->pid(), SIGKILL);
  a->Stop();
  hold_a.DropStalled();  // a's connection ends mid-response
  fetch.join();
  ASSERT_EQ(first.exit_code, 0) << first.err << nginx.AccessLog() << nginx.ErrorLog();
  const auto report = ParseReport(first.out);
  EXPECT_GE(report.retries(), 1u);
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(ReadBytes(tmp_ / "first.ply"), expected);

  // --- fetch 2: the same packets, through b, now cached -------------------
  r = RunCli({"fetch", url, "--order", "rd", "--out", (tmp_ / "second.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadBytes(tmp_ / "second.ply"), expected);
  // The container too, whole, for the Range and ETag checks below.
  const auto container = HttpGet(nginx.port(), "/v1/meshes/" + id + "/container");
  ASSERT_EQ(container.status, 200u);
  EXPECT_EQ(container.Header("x-cache-status"), "MISS");
  const std::string etag = container.Header("etag");
  ASSERT_FALSE(etag.empty());

  // --- every replica stopped: fetch 3 comes from nginx's cache alone ------
  EXPECT_EQ(b->Stop(), 0);
  const size_t before = client_side.Transcript().size();
  r = RunCli({"fetch", url, "--order", "rd", "--out", (tmp_ / "third.ply").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err << nginx.AccessLog();
  EXPECT_EQ(ReadBytes(tmp_ / "third.ply"), expected);
  EXPECT_EQ(ParseReport(r.out).retries(), 0u);
  const auto statuses = CacheStatuses(client_side.Transcript().substr(before));
  ASSERT_FALSE(statuses.empty());
  for (const auto& s : statuses) EXPECT_EQ(s, "HIT");

  // Range from the cached container, and ETag revalidation, by nginx.
  const auto range = HttpGet(nginx.port(), "/v1/meshes/" + id + "/container",
                             {{"Range", "bytes=100-1099"}});
  EXPECT_EQ(range.status, 206u);
  EXPECT_EQ(range.Header("x-cache-status"), "HIT");
  EXPECT_EQ(range.body, container.body.substr(100, 1000));
  EXPECT_EQ(range.Header("content-range"),
            "bytes 100-1099/" + std::to_string(container.body.size()));
  const auto not_modified =
      HttpGet(nginx.port(), "/v1/meshes/" + id + "/container", {{"If-None-Match", etag}});
  EXPECT_EQ(not_modified.status, 304u);
  EXPECT_EQ(not_modified.Header("x-cache-status"), "HIT");
  // The listing is never cached: with no replica it fails.
  EXPECT_EQ(HttpGet(nginx.port(), "/v1/meshes").status, 502u);
}

}  // namespace
}  // namespace meshwave
