// Child processes for tests that start real servers (PostgreSQL, nginx):
// spawned with stdout and stderr to a log, optionally as an unprivileged
// user (PostgreSQL refuses to run as root), killed with the test process
// if it dies (PR_SET_PDEATHSIG), and stopped by signal with a deadline.
#ifndef MESHWAVE_TESTS_SERVER_CHILD_PROCESS_TESTONLY_H_
#define MESHWAVE_TESTS_SERVER_CHILD_PROCESS_TESTONLY_H_

#include <arpa/inet.h>
#include <fcntl.h>
#include <grp.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace meshwave::testing {

// The account to run servers as when the test runs as root.
struct Account {
  uid_t uid = 0;
  gid_t gid = 0;
};
inline std::optional<Account> UnprivilegedAccount() {
  if (::geteuid() != 0) return std::nullopt;  // already unprivileged
  const passwd* pw = ::getpwnam("nobody");
  if (pw == nullptr) return std::nullopt;
  return Account{pw->pw_uid, pw->pw_gid};
}

// Starts `argv` (argv[0] a path) with stdout and stderr appended to `log`,
// as `account` when given. -1 when fork fails; an exec failure shows as
// exit code 127.
inline pid_t SpawnChild(const std::vector<std::string>& argv, const std::filesystem::path& log,
                        std::optional<Account> account = std::nullopt) {
  std::vector<std::string> copy(argv);
  std::vector<char*> args;
  for (auto& a : copy) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  // Child: only async-signal-safe calls from here on.
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::dup2(fd, 1);
    ::dup2(fd, 2);
  }
  ::setpgid(0, 0);  // signals to the test's group do not reach it twice
  if (account) {
    if (::setgroups(0, nullptr) != 0 || ::setgid(account->gid) != 0 ||
        ::setuid(account->uid) != 0) {
      ::_exit(126);
    }
  }
  // After the identity change, which clears it.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(125);
  ::execv(args[0], args.data());
  ::_exit(127);
}

// Waits for `pid`; its exit code, or -1 for a signal or the timeout (the
// child is then killed).
inline int WaitChild(pid_t pid, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (r < 0) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

// Sends `signal`, waits up to `grace`, then SIGKILL. The exit code or -1.
inline int StopChild(pid_t pid, int signal, std::chrono::milliseconds grace) {
  if (pid <= 0) return -1;
  ::kill(pid, signal);
  return WaitChild(pid, grace);
}

// A 127.0.0.1 port nothing listened on a moment ago. The caller retries
// when another process takes it first.
inline uint16_t FreeLoopbackPort() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  uint16_t port = 0;
  socklen_t len = sizeof a;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0) {
    port = ntohs(a.sin_port);
  }
  ::close(fd);
  return port;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_SERVER_CHILD_PROCESS_TESTONLY_H_
