// `meshwave info FILE --json` read back as the MeshInfo message it prints.
#ifndef MESHWAVE_TESTS_E2E_MESH_INFO_TESTONLY_H_
#define MESHWAVE_TESTS_E2E_MESH_INFO_TESTONLY_H_

#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "e2e/cli_runner.h"
#include "meshwave.pb.h"

namespace meshwave::testing {

inline proto::MeshInfo InfoOf(const std::filesystem::path& file) {
  const auto r = RunCli({"info", file.string(), "--json"});
  EXPECT_EQ(r.exit_code, 0) << file << ": " << r.err;
  proto::MeshInfo info;
  const auto status = google::protobuf::util::JsonStringToMessage(r.out, &info);
  EXPECT_TRUE(status.ok()) << status.ToString() << "\n" << r.out;
  return info;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_E2E_MESH_INFO_TESTONLY_H_
