// The fixture of the HTTP API's end-to-end tests (server_http_test.cpp,
// server_catalog_http_test.cpp): a meshwave-server on its own copy of a
// catalog of the four sample entries, uploads allowed with kToken.
#ifndef MESHWAVE_TESTS_SERVER_SERVER_HTTP_FIXTURE_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_SERVER_HTTP_FIXTURE_TESTONLY_H_

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "catalog_api.pb.h"
#include "e2e/cli_runner.h"
#include "http_client_testonly.h"
#include "sample_catalog_testonly.h"
#include "server_process_testonly.h"
#include "test_data.h"

namespace meshwave::testing {

inline constexpr char kToken[] = "test-token-1234";

// The repository's samples (no ../shared needed): elephant.off (irregular:
// remeshed), holes.off (semi-regular, 2 levels), and two copies of
// holes.off under other names in `dir`, which encode to other containers
// (the name is in the header): four entries.
inline std::vector<std::filesystem::path> TestMeshes(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> meshes = {SampleMesh("elephant.off"), SampleMesh("holes.off")};
  for (const char* name : {"holes_patch.off", "holes_copy.off"}) {
    std::filesystem::copy_file(SampleMesh("holes.off"), dir / name,
                               std::filesystem::copy_options::overwrite_existing);
    meshes.push_back(dir / name);
  }
  return meshes;
}

inline proto::MeshList ParseList(const std::string& json) {
  proto::MeshList list;
  EXPECT_TRUE(google::protobuf::util::JsonStringToMessage(json, &list).ok()) << json;
  return list;
}

inline bool IsJsonError(const HttpReply& r) {
  return r.Header("content-type") == "application/json" &&
         r.body.find("\"error\"") != std::string::npos;
}

class ServerHttpTest : public ::testing::Test {
 protected:
  void SetUp() override {
    work_ = tmp_ / "work";
    std::filesystem::create_directories(work_);
    catalog_ = tmp_ / "catalog";
    // Every test changes its own copy; the default fidelity's denser
    // remesh is tested by UploadWithAFidelity... and tests/server/ingest_test.
    ASSERT_NO_FATAL_FAILURE(CopySampleCatalog(catalog_, TestMeshes(work_)));
    server_ = std::make_unique<ServerProcess>(
        catalog_, work_, std::vector<std::string>{std::string("MESHWAVE_UPLOAD_TOKEN=") + kToken});
    ASSERT_TRUE(server_->running()) << ReadBytes(server_->log());
    port_ = server_->port();
    const HttpReply list = HttpGet(port_, "/v1/meshes");
    ASSERT_EQ(list.status, 200u);
    const proto::MeshList meshes = ParseList(list.body);
    for (const auto& m : meshes.meshes()) ids_[m.name()] = m.id();
    ASSERT_EQ(ids_.size(), 4u) << list.body;
  }

  void TearDown() override {
    if (server_) {
      EXPECT_EQ(server_->Stop(), 0) << ReadBytes(server_->log());
    }
  }

  std::string Container(const std::string& id) {
    const HttpReply r = HttpGet(port_, "/v1/meshes/" + id + "/container");
    EXPECT_EQ(r.status, 200u);
    return r.body;
  }

  TempDir tmp_;
  std::filesystem::path work_, catalog_;
  std::unique_ptr<ServerProcess> server_;
  uint16_t port_ = 0;
  std::map<std::string, std::string> ids_;  // name -> id
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_SERVER_HTTP_FIXTURE_TESTONLY_H_
