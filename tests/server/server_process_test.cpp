// The meshwave-server process outside serving requests: a bad config file
// refused at start, and a catalog left consistent by an ingest killed with
// SIGKILL (served again after a restart, completed by a second ingest).
// Built into server_http_test, whose helpers and labels it shares.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "catalog.h"
#include "catalog_api.pb.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "meshwave/container.h"
#include "server_process_testonly.h"
#include "sha256.h"
#include "test_data.h"

namespace meshwave::testing {
namespace {

using server::Sha256Hex;

TEST(ServerStartTest, RejectsABadConfigFile) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "w");
  std::ofstream(tmp / "w/bad.conf") << "threads: many\n";
  const pid_t pid = SpawnServer({"--catalog", (tmp / "c").string(), "--config",
                                 (tmp / "w/bad.conf").string()},
                                tmp / "w/log");
  EXPECT_EQ(WaitExit(pid), 1);
  EXPECT_NE(ReadBytes(tmp / "w/log").find("bad.conf"), std::string::npos);
}

// kill -9 of an ingest run, then a restart: every row has its file, no
// file lacks a row, and every committed entry is served.
TEST(ServerCrashTest, KilledIngestLeavesConsistentCatalog) {
  TempDir tmp;
  const auto work = tmp / "work";
  const auto catalog_dir = tmp / "catalog";
  std::filesystem::create_directories(work);
  // --fidelity 0: one remesh a file (the default's denser remeshes are
  // tested in ingest_test; this test is about the catalog after a kill).
  std::vector<std::string> args = {"ingest", "--catalog", catalog_dir.string(), "--fidelity",
                                   "0", SampleMesh("holes.off").string()};
  // Copies under other names encode to other containers (the name is in
  // the header), so each is a new entry.
  for (int i = 0; i < 6; ++i) {
    const auto copy = work / ("elephant" + std::to_string(i) + ".off");
    std::filesystem::copy_file(SampleMesh("elephant.off"), copy);
    args.push_back(copy.string());
  }
  const pid_t ingest = SpawnServer(args, work / "ingest.log");
  ASSERT_GT(ingest, 0);
  const auto containers = catalog_dir / "containers";
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  auto count_files = [&] {
    size_t n = 0;
    std::error_code ec;
    for (const auto& f : std::filesystem::directory_iterator(containers, ec)) {
      n += f.path().extension() == ".mwv" ? 1 : 0;
    }
    return n;
  };
  while (count_files() < 3 && std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(ingest, SIGKILL);
  EXPECT_EQ(WaitExit(ingest), -1);  // killed, not finished
  // What a crash between rename and insert, or inside a write, leaves.
  std::ofstream(containers / (std::string(64, 'b') + ".mwv")) << "renamed, never committed";
  std::ofstream(containers / ".tmp-999999-0-x.mwv") << "half written";

  ServerProcess server(catalog_dir, work);
  ASSERT_TRUE(server.running()) << ReadBytes(server.log());
  const HttpReply list = HttpGet(server.port(), "/v1/meshes");
  ASSERT_EQ(list.status, 200u);
  proto::MeshList entries;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(list.body, &entries).ok()) << list.body;
  EXPECT_GE(entries.meshes_size(), 2);
  std::set<std::string> expected_files;
  for (const auto& m : entries.meshes()) {
    expected_files.insert(m.sha256() + ".mwv");
    const HttpReply c = HttpGet(server.port(), "/v1/meshes/" + m.id() + "/container");
    ASSERT_EQ(c.status, 200u) << m.id();
    EXPECT_EQ(Sha256Hex(c.body), m.sha256());
    EXPECT_TRUE(ParseContainer(c.body).ok());
  }
  std::set<std::string> files;
  for (const auto& f : std::filesystem::directory_iterator(containers)) {
    files.insert(f.path().filename().string());
  }
  EXPECT_EQ(files, expected_files);
  EXPECT_EQ(server.Stop(), 0);

  // Ingesting again completes the catalog.
  const pid_t again = SpawnServer(args, work / "ingest2.log");
  EXPECT_EQ(WaitExit(again, std::chrono::seconds(120)), 0) << ReadBytes(work / "ingest2.log");
  auto catalog = server::Catalog::Open(catalog_dir);
  ASSERT_TRUE(catalog.ok());
  EXPECT_EQ(*(*catalog)->Count(), 7u);
}

}  // namespace
}  // namespace meshwave::testing
