// The tests' child processes die with the test process, however it ends
// (tests/process/child_process_testonly.h): a process that starts a real
// meshwave-server and a shell with a grandchild, then aborts, faults,
// exits, throws or is terminated, leaves none of them running.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "e2e/cli_runner.h"
#include "server/server_process_testonly.h"

namespace meshwave::testing {
namespace {

bool GoneWithin(pid_t pid, std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (ProcessRuns(pid)) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

class ChildProcessTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ChildProcessTest, NothingOutlivesATestProcessThatDies) {
  const std::string mode = GetParam();
  TempDir dir;
  // Under the sanitizers its crash is meant: its reports go to its own
  // directory, not to the stage's (tools/sanitize.sh fails on any), and the
  // objects it leaks on purpose are no finding.
  const pid_t test = SpawnChild(
      {DieWithChildrenPath().string(), mode, dir.path().string()}, dir / "test.log",
      std::nullopt,
      {"ASAN_OPTIONS=detect_leaks=0:log_path=" + (dir / "asan").string(),
       "UBSAN_OPTIONS=log_path=" + (dir / "ubsan").string()});
  ASSERT_GT(test, 0);
  const int code = WaitChild(test, std::chrono::seconds(60));
  const std::string log = ReadBytes(dir / "test.log");
  if (mode == "exit") {
    EXPECT_EQ(code, 4) << log;
  } else {
    // A signal (-1), or a sanitizer's report and its exit code.
    EXPECT_NE(code, 0) << log;
  }
  pid_t server = 0, shell = 0, grandchild = 0;
  std::ifstream(dir / "pids") >> server >> shell;
  std::ifstream(dir / "grandchild") >> grandchild;
  // With SIGKILL no handler runs: the kernel stops the children
  // (PR_SET_PDEATHSIG), not their children. The shell's group is then the
  // test's to stop, whatever the checks below say.
  struct GroupKiller {
    pid_t group;
    ~GroupKiller() {
      if (group > 0) ::kill(-group, SIGKILL);
    }
  };
  const GroupKiller cleanup{mode == "sigkill" ? shell : 0};
  ASSERT_GT(server, 0) << log;
  ASSERT_GT(shell, 0) << log;
  ASSERT_GT(grandchild, 0) << log;
  EXPECT_TRUE(GoneWithin(server, std::chrono::seconds(5)))
      << "meshwave-server " << server << "\n"
      << log;
  EXPECT_TRUE(GoneWithin(shell, std::chrono::seconds(5)))
      << "sh " << shell << "\n"
      << log;
  if (mode != "sigkill") {
    EXPECT_TRUE(GoneWithin(grandchild, std::chrono::seconds(5)))
        << "grandchild " << grandchild << "\n"
        << log;
  }
}

std::string ModeName(const ::testing::TestParamInfo<std::string>& param) {
  return param.param;
}

INSTANTIATE_TEST_SUITE_P(Ends, ChildProcessTest,
                         ::testing::Values("abort", "segfault", "exit", "throw",
                                           "sigterm", "sigkill"),
                         ModeName);

// A child that exits by itself is reaped and leaves the registry: the
// registry's atexit handler never signals a pid that may be reused.
TEST(ChildProcessRegistryTest, AReapedChildLeavesTheRegistry) {
  TempDir dir;
  const pid_t pid = SpawnChild({"/bin/sh", "-c", "exit 7"}, dir / "log");
  ASSERT_GT(pid, 0);
  size_t listed = 0;
  for (const auto& slot : child_registry::slots) listed += slot.load() == pid;
  EXPECT_EQ(listed, 1u);
  EXPECT_EQ(WaitChild(pid, std::chrono::seconds(10)), 7);
  listed = 0;
  for (const auto& slot : child_registry::slots) listed += slot.load() == pid;
  EXPECT_EQ(listed, 0u);
}

// The group is stopped with its leader: StopChild leaves no grandchild.
TEST(ChildProcessRegistryTest, StoppingAChildStopsItsGroup) {
  TempDir dir;
  const pid_t pid = SpawnChild(
      {"/bin/sh", "-c",
       "sleep 600 & echo $! > '" + (dir / "grandchild").string() + "'; wait"},
      dir / "log");
  pid_t grandchild = 0;
  for (int i = 0; i < 500 && grandchild == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream(dir / "grandchild") >> grandchild;
  }
  ASSERT_GT(grandchild, 0);
  StopChild(pid, SIGTERM, std::chrono::seconds(5));
  EXPECT_TRUE(GoneWithin(grandchild, std::chrono::seconds(5)));
}

}  // namespace
}  // namespace meshwave::testing
