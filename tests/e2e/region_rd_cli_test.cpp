// End-to-end: `meshwave region-rd` as a user runs it on a stream with
// precincts: a table whose region order is ahead of the rd order, and
// clear errors for what it cannot measure.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "e2e/cli_runner.h"

namespace meshwave {
namespace {

using testing::RunCli;
using testing::TempDir;

TEST(RegionRdCliTest, TheRegionOrderIsAheadOnEveryRegionOfTheTable) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  const auto stream = (dir / "holes.mwv").string();
  // Small precincts: holes.off's finest subband has about 12,000
  // coefficients, 24 precincts of 512.
  auto r = RunCli({"encode", in.string(), stream, "--precinct-size", "512"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunCli({"region-rd", stream, "--shares", "0.1", "--seeds", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Two rows "10% #k  vertices  a / b  c / d  e / f   rd / region (ratio)".
  std::istringstream lines(r.out);
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("10% #", 0) != 0) continue;
    ++rows;
    double rd_bytes = 0, region_bytes = 0, ratio = 0;
    const size_t tail = line.rfind("   ");
    ASSERT_NE(tail, std::string::npos) << line;
    ASSERT_EQ(std::sscanf(line.c_str() + tail, " %lf / %lf (%lf)", &rd_bytes, &region_bytes,
                          &ratio),
              3)
        << line;
    EXPECT_LT(region_bytes, rd_bytes) << line;
    EXPECT_NEAR(ratio, region_bytes / rd_bytes, 0.01) << line;
  }
  EXPECT_EQ(rows, 2) << r.out;
}

TEST(RegionRdCliTest, AnIncompleteStreamOrABadRegionIsAClearError) {
  TempDir dir;
  const auto in = testing::SampleMesh("holes.off");
  const auto stream = (dir / "holes.mwv").string();
  ASSERT_EQ(RunCli({"encode", in.string(), stream}).exit_code, 0);
  // A stream cut short.
  const auto cut = (dir / "cut.mwv").string();
  const std::string bytes = testing::ReadBytes(stream);
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  auto r = RunCli({"region-rd", cut});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("container"), std::string::npos) << r.err;
  r = RunCli({"region-rd", stream, "--region", "1,2,3"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("region"), std::string::npos) << r.err;
  r = RunCli({"region-rd", stream, "--shares", "0.1,x"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--shares"), std::string::npos) << r.err;
  EXPECT_EQ(RunCli({"region-rd", "--help"}).exit_code, 0);
}

}  // namespace
}  // namespace meshwave
