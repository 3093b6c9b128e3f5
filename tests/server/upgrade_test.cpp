// The whole upgrade (docs/DEPLOY.md, "Upgrades"), against both catalog
// backends: a catalog as the previous release wrote it (genuine version-6
// containers with their originals, tests/data/upgrade/, beside a mesh of
// this version) is served by this build under HTTP load (wrk) and
// WebSocket load while `meshwave-server reencode` runs; the first reencode
// is killed with SIGKILL after its first mesh and a second one finishes.
// No request may fail, no row may lose its container at any point, and at
// the end every mesh is served in the current format version.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <fstream>
#include <regex>
#include <thread>

#include "catalog.h"
#include "catalog_api.pb.h"
#include "core/durable_file.h"
#include "e2e/cli_runner.h"
#include "encode_settings.h"
#include "ingest.h"
#include "mesh_identity.h"
#include "meshwave/container.h"
#include "server/catalog_backends_testonly.h"
#include "server/http_client_testonly.h"
#include "server/server_process_testonly.h"
#include "server/ws_client_testonly.h"
#include "sha256.h"
#include "test_data.h"

namespace meshwave::testing {
namespace {

using server::Catalog;
using server::CatalogEntry;

// The previous release's settings: precincts came with version 7.
constexpr char kOldSettings[] = "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=0 split=48";

struct OldMesh {
  std::string name;   // the mesh's name (the container's header holds it)
  std::string file;   // its original among the samples (data/)
  std::string container;  // tests/data/upgrade/
};

const std::vector<OldMesh> kOldMeshes = {
    {"holes", "holes.off", "holes.v6.mwv"},
    {"elephant", "elephant.off", "elephant.v6.mwv"},
};

// Writes a row, its original and its container as a build of the previous
// format version that kept originals would have.
void AddOldMesh(Catalog& catalog, const OldMesh& m) {
  const std::string original_bytes = ReadBytes(SampleMesh(m.file));
  const std::vector<server::OriginalPart> parts = {{m.file, original_bytes}};
  auto original = server::DescribeOriginal(parts, m.file);
  ASSERT_TRUE(original.ok());
  ASSERT_TRUE(server::WriteOriginal(catalog.store_dir(), *original, parts).ok());
  const std::string container = ReadBytes(TestData("upgrade/" + m.container));
  auto parsed = ParseContainer(container);
  ASSERT_TRUE(parsed.ok()) << m.container << ": " << parsed.status().ToString();
  ASSERT_EQ(parsed->header.format_version, 6u) << m.container;
  CatalogEntry e;
  e.sha256 = server::Sha256Hex(container);
  e.id = server::MeshIdOf(original->digest, kOldSettings, m.name);
  e.name = m.name;
  e.source = m.file;
  e.vertices = parsed->header.vertices;
  e.faces = parsed->header.faces;
  e.levels = parsed->header.transform.levels;
  e.packets = static_cast<uint32_t>(parsed->ids.size());
  e.bytes = container.size();
  e.container = "containers/" + e.sha256 + ".mwv";
  e.created_unix = 1;
  e.format_version = 6;
  e.original = original->digest;
  e.settings = kOldSettings;
  ASSERT_TRUE(WriteFileDurably(catalog.ContainerPath(e), container).ok());
  ASSERT_TRUE(catalog.Insert(e, &*original).ok());
}

// Every row names a container on disk that parses whole.
void ExpectEveryRowServable(Catalog& catalog) {
  auto rows = catalog.List(100, 0);
  ASSERT_TRUE(rows.ok());
  for (const CatalogEntry& e : *rows) {
    const std::string bytes = ReadBytes(catalog.ContainerPath(e));
    ASSERT_FALSE(bytes.empty()) << e.id << ": " << e.container << " is gone";
    EXPECT_EQ(server::Sha256Hex(bytes), e.sha256) << e.id;
    EXPECT_TRUE(ParseContainer(bytes).ok()) << e.id;
  }
}

struct LoadCounts {
  std::atomic<uint64_t> requests{0}, failed{0}, sessions{0}, failed_sessions{0};
  std::mutex mutex;
  std::string first_failure;
  void Fail(const std::string& why) {
    ++failed;
    std::lock_guard lock(mutex);
    if (first_failure.empty()) first_failure = why;
  }
};

// wrk in bursts of two seconds over every endpoint of every mesh, until
// `stop`: its requests, and those answered other than 2xx/3xx or not at all.
void HttpLoad(uint16_t port, const std::vector<std::string>& ids, const std::filesystem::path& dir,
              std::atomic<bool>& stop, LoadCounts& counts) {
  std::string paths = "\"/v1/meshes\"";
  for (const std::string& id : ids) {
    const std::string m = "/v1/meshes/" + id;
    for (const std::string& p : {m, m + "/header", m + "/stream?budget=3000",
                                 m + "/stream?order=rd&budget=20000", m + "/container",
                                 m + "/packets/0"}) {
      paths += ", \"" + p + "\"";
    }
  }
  const auto script = dir / "load.lua";
  std::ofstream(script) << "local paths = {" << paths << "}\n"
                        << "local i = 0\n"
                        << "request = function()\n  i = i % #paths + 1\n"
                        << "  return wrk.format(\"GET\", paths[i])\nend\n"
                        << "done = function(s, latency, requests)\n"
                        << "  io.write(string.format(\"MW %d %d %d\\n\", s.requests, s.errors.status,"
                        << " s.errors.connect + s.errors.read + s.errors.write + s.errors.timeout))\n"
                        << "end\n";
  for (int burst = 0; !stop; ++burst) {
    const auto out = dir / ("wrk-" + std::to_string(burst) + ".txt");
    const pid_t pid = SpawnChild({"/usr/bin/wrk", "-t1", "-c4", "-d2s", "-s", script.string(),
                                  "http://127.0.0.1:" + std::to_string(port)},
                                 out);
    if (WaitChild(pid, std::chrono::seconds(30)) != 0) {
      counts.Fail("wrk did not finish: " + ReadBytes(out));
      return;
    }
    std::smatch match;
    const std::string text = ReadBytes(out);
    if (!std::regex_search(text, match, std::regex("MW (\\d+) (\\d+) (\\d+)"))) {
      counts.Fail("wrk printed no summary: " + text);
      return;
    }
    counts.requests += std::stoull(match[1]);
    const uint64_t bad = std::stoull(match[2]) + std::stoull(match[3]);
    if (bad > 0) counts.Fail(std::to_string(bad) + " failed in burst " + std::to_string(burst));
  }
}

// WebSocket sessions one after the other, each streaming a whole mesh:
// every one must end in Done with every packet its Selection announced.
void WebSocketLoad(uint16_t port, const std::vector<std::string>& ids, std::atomic<bool>& stop,
                   LoadCounts& counts) {
  for (size_t n = 0; !stop; ++n) {
    WsTestClient ws(port);
    ++counts.sessions;
    if (!ws.open()) {
      ++counts.failed_sessions;
      counts.Fail("WebSocket upgrade refused");
      continue;
    }
    proto::ClientMessage start;
    start.mutable_start()->set_mesh_id(ids[n % ids.size()]);
    start.mutable_start()->set_order("quality");
    ws.Send(start);
    const auto messages = ws.ReadUntilDone();
    size_t packets = 0;
    uint64_t announced = 0;
    bool done = false;
    std::string error;
    for (const auto& m : messages) {
      if (m.has_start()) {
        announced = m.start().selection().next_cursor() - m.start().selection().from_cursor();
      }
      if (m.has_packet()) ++packets;
      if (m.has_done()) done = true;
      if (m.has_error()) error = m.error().message();
    }
    if (!done || packets != announced || !error.empty()) {
      ++counts.failed_sessions;
      counts.Fail("WebSocket session of " + ids[n % ids.size()] + ": " +
                  std::to_string(packets) + " of " + std::to_string(announced) + " packets" +
                  (error.empty() ? "" : ", error " + error));
    }
    ws.Close();
  }
}

using UpgradeTest = CatalogBackendTest;

TEST_P(UpgradeTest, ReencodesUnderLoadThroughAKillWithoutAFailedRequest) {
  if (!std::filesystem::exists("/usr/bin/wrk")) {
    if (std::getenv("CI") != nullptr) FAIL() << "wrk is missing (CI must run the upgrade test)";
    GTEST_SKIP() << "wrk is not installed (deploy/install-deps.sh installs it)";
  }
  std::vector<std::string> ids;
  {
    auto catalog = OpenCatalog();
    ASSERT_TRUE(catalog);
    for (const OldMesh& m : kOldMeshes) ASSERT_NO_FATAL_FAILURE(AddOldMesh(*catalog, m));
    auto current = server::IngestMeshFile(*catalog, SampleMesh("holes.off"), "current");
    ASSERT_TRUE(current.ok()) << current.status().ToString();
    auto rows = catalog->List(100, 0);
    ASSERT_TRUE(rows.ok());
    for (const CatalogEntry& e : *rows) ids.push_back(e.id);
    ASSERT_EQ(ids.size(), 3u);
  }
  const auto work = tmp_ / "work";
  std::filesystem::create_directories(work);
  std::vector<std::string> extra;
  if (!store().empty()) extra = {"--store", store().string()};
  ServerProcess server(location(), work, {}, extra);
  ASSERT_TRUE(server.running()) << ReadBytes(server.log());
  // The previous version's containers are served before anything else.
  for (const std::string& id : ids) {
    const HttpReply r = HttpGet(server.port(), "/v1/meshes/" + id + "/stream?budget=5000");
    ASSERT_EQ(r.status, 200u) << id << ": " << r.body;
  }

  std::atomic<bool> stop{false};
  LoadCounts http, ws;
  std::thread http_load([&] { HttpLoad(server.port(), ids, work, stop, http); });
  std::vector<std::thread> ws_load;
  for (int i = 0; i < 2; ++i) {
    ws_load.emplace_back([&] { WebSocketLoad(server.port(), ids, stop, ws); });
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));

  std::vector<std::string> reencode = {"reencode", "--catalog", location(), "--threads", "1"};
  reencode.insert(reencode.end(), extra.begin(), extra.end());
  // The first run is killed once it has swapped a mesh in.
  const auto first_log = work / "reencode-1.log";
  const pid_t first = SpawnServer(reencode, first_log);
  ASSERT_GT(first, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (ReadBytes(first_log).find("re-encoded in") == std::string::npos &&
         ProcessRuns(first) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(first, SIGKILL);
  WaitExit(first);
  const std::string first_text = ReadBytes(first_log);
  ASSERT_NE(first_text.find("re-encoded in"), std::string::npos) << first_text;
  {
    SCOPED_TRACE("after the kill");
    auto catalog = OpenCatalog();
    ASSERT_TRUE(catalog);
    ExpectEveryRowServable(*catalog);
  }
  // The second run goes on with what is left.
  const auto second_log = work / "reencode-2.log";
  const pid_t second = SpawnServer(reencode, second_log);
  ASSERT_EQ(WaitExit(second, std::chrono::seconds(300)), 0) << ReadBytes(second_log);
  const std::string second_text = ReadBytes(second_log);
  EXPECT_NE(second_text.find(", 0 failed"), std::string::npos) << second_text;
  // Replicas see the swap within catalog_poll_milliseconds (1 s).
  std::this_thread::sleep_for(std::chrono::seconds(3));
  stop = true;
  http_load.join();
  for (auto& t : ws_load) t.join();

  std::printf("load during the upgrade: %llu HTTP requests, %llu WebSocket sessions\n",
              static_cast<unsigned long long>(http.requests.load()),
              static_cast<unsigned long long>(ws.sessions.load()));
  EXPECT_GT(http.requests, 1000u);
  EXPECT_GT(ws.sessions, 10u);
  EXPECT_EQ(http.failed, 0u) << http.first_failure;
  EXPECT_EQ(ws.failed, 0u) << ws.first_failure;
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  ExpectEveryRowServable(*catalog);
  const proto::MeshList list = [&] {
    proto::MeshList l;
    const HttpReply r = HttpGet(server.port(), "/v1/meshes");
    EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &l).ok()) << r.body;
    return l;
  }();
  ASSERT_EQ(list.meshes_size(), 3);
  for (const auto& m : list.meshes()) {
    EXPECT_EQ(m.format_version(), kStreamFormatVersion) << m.name();
    const HttpReply r = HttpGet(server.port(), "/v1/meshes/" + m.id() + "/container");
    ASSERT_EQ(r.status, 200u);
    auto parsed = ParseContainer(r.body);
    ASSERT_TRUE(parsed.ok()) << m.name();
    EXPECT_EQ(parsed->header.format_version, kStreamFormatVersion) << m.name();
    EXPECT_EQ(r.Header("etag").find(m.sha256()), 1u);  // the ETag moved with the container
  }
  EXPECT_EQ(server.Stop(), 0) << ReadBytes(server.log());
}

// reencode_on_start: the server re-encodes its out-of-date meshes in the
// background while it serves them.
TEST_P(UpgradeTest, AServerCanReencodeInTheBackground) {
  {
    auto catalog = OpenCatalog();
    ASSERT_TRUE(catalog);
    for (const OldMesh& m : kOldMeshes) ASSERT_NO_FATAL_FAILURE(AddOldMesh(*catalog, m));
  }
  const auto work = tmp_ / "work";
  std::filesystem::create_directories(work);
  std::ofstream(work / "server.conf") << "reencode_on_start: true\ncatalog_poll_milliseconds: 200\n";
  std::vector<std::string> extra = {"--config", (work / "server.conf").string()};
  if (!store().empty()) extra.insert(extra.end(), {"--store", store().string()});
  ServerProcess server(location(), work, {}, extra);
  ASSERT_TRUE(server.running()) << ReadBytes(server.log());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  size_t current = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    proto::MeshList list;
    const HttpReply r = HttpGet(server.port(), "/v1/meshes");
    ASSERT_EQ(r.status, 200u);
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(r.body, &list).ok());
    current = 0;
    for (const auto& m : list.meshes()) {
      current += m.format_version() == kStreamFormatVersion;
      // Served all along, whichever container the row names.
      EXPECT_EQ(HttpGet(server.port(), "/v1/meshes/" + m.id() + "/stream?budget=4000").status,
                200u);
    }
    if (current == kOldMeshes.size()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(current, kOldMeshes.size()) << ReadBytes(server.log());
  // The worker's report reaches the log once it has exited.
  const std::string report = "background reencode: 2 meshes: 2 re-encoded";
  while (ReadBytes(server.log()).find(report) == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_NE(ReadBytes(server.log()).find(report), std::string::npos) << ReadBytes(server.log());
  EXPECT_EQ(server.Stop(), 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, UpgradeTest,
                         ::testing::Values(CatalogBackend::kSqlite, CatalogBackend::kPostgres),
                         CatalogBackendName);

}  // namespace
}  // namespace meshwave::testing
