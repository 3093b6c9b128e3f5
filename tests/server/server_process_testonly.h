// Starts the built meshwave-server binary (serve or ingest) as a child
// process, finds the port it bound, and stops it.
#ifndef MESHWAVE_TESTS_SERVER_SERVER_PROCESS_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_SERVER_PROCESS_TESTONLY_H_

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "process/child_process_testonly.h"
#include "test_data.h"

namespace meshwave::testing {

// Spawns meshwave-server with `args`, stdout and stderr to `log`; extra
// environment entries ("K=V") are added. Returns the pid (-1 on failure).
// A child of SpawnChild: stopped with the test whatever happens.
inline pid_t SpawnServer(const std::vector<std::string>& args, const std::filesystem::path& log,
                         const std::vector<std::string>& env = {}) {
  std::vector<std::string> argv = {ServerPath().string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return SpawnChild(argv, log, std::nullopt, env);
}

// Waits for the child to exit; its exit code, or -1 (signal, timeout).
inline int WaitExit(pid_t pid, std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
  return WaitChild(pid, timeout);
}

// A running `meshwave-server --catalog DIR --listen 127.0.0.1:0`.
class ServerProcess {
 public:
  ServerProcess(const std::filesystem::path& catalog, const std::filesystem::path& work,
                const std::vector<std::string>& env = {}, std::vector<std::string> extra = {}) {
    port_file_ = work / "port";
    log_ = work / "server.log";
    std::filesystem::remove(port_file_);
    std::vector<std::string> args = {"--catalog", catalog.string(), "--listen", "127.0.0.1:0",
                                     "--threads", "2", "--port-file", port_file_.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    pid_ = SpawnServer(args, log_, env);
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (pid_ > 0 && std::chrono::steady_clock::now() < end) {
      std::ifstream in(port_file_);
      int port = 0;
      if (in >> port && port > 0) {
        port_ = static_cast<uint16_t>(port);
        break;
      }
      if (!ProcessRuns(pid_)) {  // exited early: reaped, its code in the log
        WaitChild(pid_, std::chrono::seconds(1));
        pid_ = -1;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ~ServerProcess() {
    if (pid_ > 0) Stop();
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  bool running() const { return pid_ > 0 && port_ != 0; }
  uint16_t port() const { return port_; }
  pid_t pid() const { return pid_; }
  const std::filesystem::path& log() const { return log_; }
  // SIGTERM, then the exit code (0 for a graceful stop).
  int Stop() {
    if (pid_ <= 0) return -1;
    ::kill(pid_, SIGTERM);
    const int code = WaitExit(pid_);
    pid_ = -1;
    return code;
  }

 private:
  pid_t pid_ = -1;
  uint16_t port_ = 0;
  std::filesystem::path port_file_, log_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_SERVER_PROCESS_TESTONLY_H_
