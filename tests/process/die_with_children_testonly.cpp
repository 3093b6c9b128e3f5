// A test process that dies badly: starts a meshwave-server (ServerProcess)
// and a shell that starts a grandchild, writes their pids, then ends the
// way argv[1] says, without stopping anything. child_process_test runs it
// and checks that nothing it started outlives it.
//   die_with_children_testonly MODE DIR
//   MODE: abort | segfault | exit | throw | sigterm | sigkill
#include <signal.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>

#include "server/server_process_testonly.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr,
                 "usage: %s abort|segfault|exit|throw|sigterm|sigkill DIR\n",
                 argv[0]);
    return 2;
  }
  using namespace meshwave::testing;
  const std::string mode = argv[1];
  const std::filesystem::path dir = argv[2];
  std::filesystem::create_directories(dir / "server");
  // Leaked on purpose: no destructor may be what stops them.
  auto* server = new ServerProcess(dir / "catalog", dir / "server");
  if (!server->running()) {
    std::fprintf(stderr, "the server did not start\n");
    return 3;
  }
  // A group with a grandchild: stopping the child alone would leave it.
  const pid_t shell = SpawnChild(
      {"/bin/sh", "-c",
       "sleep 600 & echo $! > '" + (dir / "grandchild").string() + "'; wait"},
      dir / "shell.log");
  // The shell creates the file before it writes the pid: wait for the pid.
  pid_t grandchild = 0;
  for (int i = 0; i < 3000 && grandchild <= 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream(dir / "grandchild") >> grandchild;
  }
  std::ofstream(dir / "pids") << server->pid() << " " << shell << "\n";
  if (mode == "abort") std::abort();
  if (mode == "segfault") {
    volatile int* volatile null = nullptr;
    *null = 1;  // a real fault, not a sent signal
  }
  if (mode == "exit") std::exit(4);
  if (mode == "throw") throw std::runtime_error("uncaught");
  if (mode == "sigterm") ::raise(SIGTERM);  // as ctest's timeout does
  if (mode == "sigkill")
    ::raise(SIGKILL);  // nothing runs: PR_SET_PDEATHSIG only
  std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
  return 2;
}
