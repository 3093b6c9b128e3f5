// `meshwave fetch --region` and `meshwave refine --view/--region` against
// the real server over HTTP and WebSocket (docs/API.md, "Region
// requests"): a sequence of regions, each continuing from the state file,
// ends in exactly the mesh the complete stream decodes to; the client
// refuses any unit sent twice, so the sequence succeeding shows none was.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "catalog_api.pb.h"
#include "client_state.pb.h"
#include "e2e/cli_runner.h"
#include "server/http_client_testonly.h"
#include "server/sample_catalog_testonly.h"
#include "server/server_process_testonly.h"

namespace meshwave {
namespace {

using testing::HttpGet;
using testing::RunCli;
using testing::ServerProcess;
using testing::TempDir;

// Runs the CLI, expecting success and a JSON FetchReport on stdout.
proto::FetchReport RunFetch(const std::vector<std::string>& args) {
  const auto r = RunCli(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  proto::FetchReport report;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(r.out, &report).ok()) << r.out;
  return report;
}

class RegionFetchTest : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const auto catalog = *dir_ / "catalog";
    ASSERT_NO_FATAL_FAILURE(testing::CopySampleCatalog(
        catalog, {testing::SampleMesh("elephant.off")},
        // The remesh's regions: without the original layer, which is
        // global and last in every order (docs/FORMAT.md 2.5).
        {"--precinct-size", "48", "--split-bytes", "4", "--no-original"}));
    std::filesystem::create_directories(*dir_ / "server");
    server_ = new ServerProcess(catalog, *dir_ / "server");
    ASSERT_TRUE(server_->running()) << testing::ReadBytes(server_->log());
    proto::MeshList meshes;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(
                    HttpGet(server_->port(), "/v1/meshes").body, &meshes)
                    .ok());
    id_ = new std::string(meshes.meshes(0).id());
    bytes_ = meshes.meshes(0).bytes();
  }
  static void TearDownTestSuite() {
    if (server_) {
      EXPECT_EQ(server_->Stop(), 0) << testing::ReadBytes(server_->log());
    }
    delete server_;
    delete dir_;
  }
  std::string Url() const {
    return GetParam() + "://127.0.0.1:" + std::to_string(server_->port()) + "/v1/meshes/" + *id_;
  }

  static inline TempDir* dir_ = nullptr;
  static inline ServerProcess* server_ = nullptr;
  static inline std::string* id_ = nullptr;
  static inline uint64_t bytes_ = 0;
};

TEST_P(RegionFetchTest, RegionsAndViewsContinueFromTheStateAndEndInTheFullMesh) {
  const auto work = *dir_ / GetParam();
  std::filesystem::create_directories(work);
  const std::string state = (work / "state.mwv").string();
  const std::string sphere = "0.3,0,0,0.4";
  const std::string view = "-3,0,0,1,0,0,40,640,480";
  proto::FetchReport first =
      RunFetch({"fetch", Url(), "--region", sphere, "--budget", std::to_string(bytes_ / 4), "--out",
           (work / "a.ply").string(), "--state", state, "--json"});
  EXPECT_EQ(first.order(), "region");
  EXPECT_FALSE(first.complete());
  EXPECT_LE(first.bytes(), bytes_ / 4);
  EXPECT_GT(first.packets(), 0u);
  proto::ClientState meta;
  ASSERT_TRUE(meta.ParseFromString(testing::ReadBytes(state + ".session")));
  EXPECT_TRUE(meta.units());
  EXPECT_FALSE(meta.held().empty());
  // The packets held whole are a container `meshwave decode` reads.
  EXPECT_EQ(RunCli({"decode", state, (work / "whole.ply").string()}).exit_code, 0);

  proto::FetchReport second = RunFetch({"refine", state, "--view", view, "--more",
                                   std::to_string(bytes_ / 5), "--json"});
  EXPECT_GT(second.packets(), first.packets());
  proto::FetchReport third = RunFetch({"refine", state, "--more", std::to_string(bytes_ / 10), "--json"});
  EXPECT_GT(third.packets(), second.packets());
  EXPECT_FALSE(third.complete());
  const std::string final_ply = (work / "final.ply").string();
  proto::FetchReport last =
      RunFetch({"refine", state, "--region", sphere, "--more", "1GiB", "--out", final_ply, "--json"});
  EXPECT_TRUE(last.complete());
  EXPECT_EQ(last.packets(), last.packets_total());

  // The complete stream's mesh, decoded from the container.
  const std::string full = (work / "full.mwv").string();
  {
    const auto body = HttpGet(server_->port(), "/v1/meshes/" + *id_ + "/container").body;
    std::ofstream(full, std::ios::binary) << body;
  }
  const std::string full_ply = (work / "full.ply").string();
  ASSERT_EQ(RunCli({"decode", full, full_ply}).exit_code, 0);
  EXPECT_EQ(testing::ReadBytes(final_ply), testing::ReadBytes(full_ply));
  // And the state's container now holds every packet.
  const std::string again_ply = (work / "again.ply").string();
  ASSERT_EQ(RunCli({"decode", state, again_ply}).exit_code, 0);
  EXPECT_EQ(testing::ReadBytes(again_ply), testing::ReadBytes(full_ply));
}

// `fetch --view V --screen-error PX`: the units that bring the view within
// PX pixels, a fraction of the stream; refining the same view at the same
// tolerance brings nothing more, a finer tolerance brings more.
TEST_P(RegionFetchTest, AScreenErrorFetchStopsWhenTheViewIsWithinIt) {
  const auto work = *dir_ / (GetParam() + "_screen");
  std::filesystem::create_directories(work);
  const std::string state = (work / "state.mwv").string();
  const std::string view = "-3,0,0,1,0,0,40,640,480";
  const proto::FetchReport first =
      RunFetch({"fetch", Url(), "--view", view, "--screen-error", "2", "--budget", "1GiB", "--out",
           (work / "a.ply").string(), "--state", state, "--json"});
  EXPECT_GT(first.packets(), 0u);
  EXPECT_LT(first.bytes(), bytes_ / 2);
  const proto::FetchReport same =
      RunFetch({"refine", state, "--view", view, "--screen-error", "2", "--more", "1GiB", "--json"});
  EXPECT_EQ(same.packets_received(), 0u) << same.bytes() << " against " << first.bytes();
  const proto::FetchReport finer =
      RunFetch({"refine", state, "--view", view, "--screen-error", "0.25", "--more", "1GiB", "--json"});
  EXPECT_GT(finer.bytes(), first.bytes());
  EXPECT_FALSE(finer.complete());
}

TEST_P(RegionFetchTest, RefusesABadRegionAndPsnrWithARegion) {
  const auto work = *dir_ / (GetParam() + "_bad");
  std::filesystem::create_directories(work);
  const std::string out = (work / "x.ply").string();
  auto r = RunCli({"fetch", Url(), "--region", "1,2,3", "--out", out});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--region"), std::string::npos) << r.err;
  r = RunCli({"fetch", Url(), "--region", "0,0,0,1", "--view", "0,0,3,0,0,-1,45,10,10", "--out", out});
  EXPECT_NE(r.exit_code, 0);
  r = RunCli({"fetch", Url(), "--region", "0,0,0,1", "--psnr", "50", "--out", out});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--psnr"), std::string::npos) << r.err;
  r = RunCli({"fetch", Url(), "--region", "0,0,0,1", "--budget", "10", "--out", out});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("header"), std::string::npos) << r.err;
}

INSTANTIATE_TEST_SUITE_P(Transports, RegionFetchTest, ::testing::Values("http", "ws"));

}  // namespace
}  // namespace meshwave
