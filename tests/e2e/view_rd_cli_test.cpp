// End-to-end: `meshwave view-rd` as a user runs it: per camera path and
// tolerance, the bytes of the screen-space-error view order, the error the
// cameras show after them (within the tolerance: the request keeps its
// promise) and the rd order's bytes; clear errors for what it cannot
// measure.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "e2e/cli_runner.h"

namespace meshwave {
namespace {

using testing::RunCli;
using testing::TempDir;

TEST(ViewRdCliTest, EveryPathIsWithinItsToleranceAfterItsViewRequests) {
  TempDir dir;
  const auto stream = (dir / "holes.mwv").string();
  auto r = RunCli({"encode", testing::SampleMesh("holes.off").string(), stream, "--precinct-size",
                   "512"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli({"view-rd", stream, "--tolerances", "1,4", "--orbit-cameras", "4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Rows "path cameras N px view_bytes worst_px rd_bytes ratio".
  std::istringstream lines(r.out);
  std::string line;
  int rows = 0;
  std::map<std::string, double> bytes;  // "path@tolerance"
  while (std::getline(lines, line)) {
    char path[16] = {};
    int cameras = 0;
    double tolerance = 0, view_bytes = 0, worst = 0, rd_bytes = 0, ratio = 0;
    if (std::sscanf(line.c_str(), "%15s %d %lf px %lf %lf %lf %lf", path, &cameras, &tolerance,
                    &view_bytes, &worst, &rd_bytes, &ratio) != 7) {
      continue;
    }
    ++rows;
    EXPECT_EQ(cameras, std::string(path) == "orbit" ? 4 : 5) << line;
    bytes[std::string(path) + "@" + std::to_string(static_cast<int>(tolerance))] = view_bytes;
    EXPECT_LE(worst, tolerance) << line;
    if (rd_bytes > 0) {
      EXPECT_NEAR(ratio, view_bytes / rd_bytes, 0.01) << line;
    }
  }
  EXPECT_EQ(rows, 4) << r.out;
  // A finer tolerance asks for more; the zoom's nearest camera sees detail
  // the base mesh does not have.
  EXPECT_GE(bytes["orbit@1"], bytes["orbit@4"]) << r.out;
  EXPECT_GE(bytes["zoom@1"], bytes["zoom@4"]) << r.out;
  EXPECT_GT(bytes["zoom@4"], 0) << r.out;
}

TEST(ViewRdCliTest, AnIncompleteStreamOrBadTolerancesAreClearErrors) {
  TempDir dir;
  const auto stream = (dir / "holes.mwv").string();
  ASSERT_EQ(RunCli({"encode", testing::SampleMesh("holes.off").string(), stream}).exit_code, 0);
  const auto cut = (dir / "cut.mwv").string();
  const std::string bytes = testing::ReadBytes(stream);
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  auto r = RunCli({"view-rd", cut});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("container"), std::string::npos) << r.err;
  for (const char* bad : {"1,x", "0", "-2", ""}) {
    r = RunCli({"view-rd", stream, "--tolerances", bad});
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_NE(r.err.find("--tolerances"), std::string::npos) << r.err;
  }
  EXPECT_EQ(RunCli({"view-rd", "--help"}).exit_code, 0);
}

}  // namespace
}  // namespace meshwave
