// Starts the built meshwave-server binary (serve or ingest) as a child
// process, finds the port it bound, and stops it.
#ifndef MESHWAVE_TESTS_SERVER_SERVER_PROCESS_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_SERVER_PROCESS_TESTONLY_H_

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "child_process_testonly.h"

extern char** environ;

namespace meshwave::testing {

inline std::filesystem::path ServerPath() { return MESHWAVE_SERVER_PATH; }

// Spawns meshwave-server with `args`, stdout and stderr to `log`; extra
// environment entries ("K=V") are added. Returns the pid (-1 on failure).
inline pid_t SpawnServer(const std::vector<std::string>& args, const std::filesystem::path& log,
                         const std::vector<std::string>& env = {}) {
  std::vector<std::string> argv_s = {ServerPath().string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s(env);
  for (char** e = environ; *e; ++e) env_s.emplace_back(*e);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
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
      if (::waitpid(pid_, nullptr, WNOHANG) == pid_) {
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
