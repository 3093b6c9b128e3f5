// Child processes of the tests (meshwave-server, PostgreSQL, nginx): the one
// place that starts and stops them. Every child
//   - runs in its own process group, so that stopping it reaches what it
//     started too (nginx's workers, PostgreSQL's backends);
//   - dies with the test process (PR_SET_PDEATHSIG: SIGKILL when the test's
//     thread that forked it exits, whatever killed it, even SIGKILL);
//   - is listed in a process-wide registry until it is reaped: an atexit
//     handler and handlers of the fatal signals (abort, segfault, ctest's
//     SIGTERM...) kill every listed group before the process goes, so that
//     a failed ASSERT in a fixture, a crash or exit() leaves nothing behind.
// Output goes to a log; a child can run as an unprivileged user
// (PostgreSQL refuses to run as root) and with extra environment entries.
#ifndef MESHWAVE_TESTS_PROCESS_CHILD_PROCESS_TESTONLY_H_
#define MESHWAVE_TESTS_PROCESS_CHILD_PROCESS_TESTONLY_H_

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

#include <array>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

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

namespace child_registry {

// Lock-free slots: the signal handlers read them. 0 is a free slot.
inline constexpr size_t kSlots = 256;
inline std::array<std::atomic<pid_t>, kSlots> slots{};

// SIGKILL to every listed child's group (and the child itself, should its
// setpgid not have happened yet). Async-signal-safe.
inline void KillAll() {
  for (auto& slot : slots) {
    const pid_t pid = slot.load();
    if (pid > 0) {
      ::kill(-pid, SIGKILL);
      ::kill(pid, SIGKILL);
    }
  }
}

inline constexpr std::array<int, 9> kFatalSignals = {
    SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGTERM, SIGINT, SIGHUP, SIGQUIT};
inline std::array<struct sigaction, kFatalSignals.size()> previous{};
// The process that installed the handlers: a child between fork and exec
// still has them, and must not kill its siblings.
inline pid_t owner = 0;

// Kills the children, then lets the signal do what it did before (the
// default action, or a sanitizer's report): the previous handler comes
// back; a fault returns to re-execute its instruction (so that handler
// sees the real fault), a sent signal (kill, raise, abort) is raised again.
inline void OnFatalSignal(int sig, siginfo_t* info, void*) {
  if (::getpid() == owner) KillAll();
  for (size_t i = 0; i < kFatalSignals.size(); ++i) {
    if (kFatalSignals[i] == sig) ::sigaction(sig, &previous[i], nullptr);
  }
  if (info == nullptr || info->si_code <= 0) ::raise(sig);
}

inline void InstallHandlersOnce() {
  static std::once_flag once;
  std::call_once(once, [] {
    owner = ::getpid();
    std::atexit(KillAll);
    for (size_t i = 0; i < kFatalSignals.size(); ++i) {
      struct sigaction sa {};
      sa.sa_sigaction = OnFatalSignal;
      sigemptyset(&sa.sa_mask);
      sa.sa_flags =
          SA_SIGINFO | SA_ONSTACK;  // SA_ONSTACK: a sanitizer's alternate stack
      ::sigaction(kFatalSignals[i], &sa, &previous[i]);
    }
  });
}

inline void Add(pid_t pid) {
  for (auto& slot : slots) {
    pid_t free = 0;
    if (slot.compare_exchange_strong(free, pid)) return;
  }
  // Full: the child still dies with its parent (PR_SET_PDEATHSIG).
}

inline void Remove(pid_t pid) {
  for (auto& slot : slots) {
    pid_t expected = pid;
    if (slot.compare_exchange_strong(expected, 0)) return;
  }
}

}  // namespace child_registry

// Starts `argv` (argv[0] a path) with stdout and stderr appended to `log`,
// as `account` when given, with `env` ("K=V") added to this process's
// environment. -1 when fork fails; a failed exec shows as exit code 127.
inline pid_t SpawnChild(const std::vector<std::string>& argv,
                        const std::filesystem::path& log,
                        std::optional<Account> account = std::nullopt,
                        const std::vector<std::string>& env = {}) {
  child_registry::InstallHandlersOnce();
  // Everything the child needs is built before fork: after it, only
  // async-signal-safe calls.
  std::vector<std::string> copy(argv);
  std::vector<char*> args;
  for (auto& a : copy) args.push_back(a.data());
  args.push_back(nullptr);
  std::vector<std::string> env_copy(env);
  for (char** e = environ; *e != nullptr; ++e) env_copy.emplace_back(*e);
  std::vector<char*> envp;
  for (auto& e : env_copy) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string log_path = log.string();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid > 0) {
    ::setpgid(pid, pid);  // also here: no window where a kill(-pid) misses it
    child_registry::Add(pid);
    return pid;
  }
  // Child.
  const int fd =
      ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd >= 0) {
    ::dup2(fd, 1);
    ::dup2(fd, 2);
  }
  ::setpgid(0, 0);
  if (account) {
    if (::setgroups(0, nullptr) != 0 || ::setgid(account->gid) != 0 ||
        ::setuid(account->uid) != 0) {
      ::_exit(126);
    }
  }
  // After the identity change, which clears it.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(125);  // the parent died before prctl
  ::execve(args[0], args.data(), envp.data());
  ::_exit(127);
}

// Waits for `pid`; its exit code, or -1 for a signal or the timeout (the
// child's group is then killed). Anything left in the child's group is
// killed once it has exited, and it leaves the registry.
inline int WaitChild(pid_t pid, std::chrono::milliseconds timeout) {
  if (pid <= 0) return -1;
  const auto end = std::chrono::steady_clock::now() + timeout;
  int status = 0;
  pid_t r = 0;
  while ((r = ::waitpid(pid, &status, WNOHANG)) == 0 &&
         std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  int code = -1;
  if (r == pid) {
    code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  } else if (r == 0) {  // the timeout
    ::kill(-pid, SIGKILL);
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  ::kill(-pid, SIGKILL);  // stragglers of its group
  child_registry::Remove(pid);
  return code;
}

// Sends `signal` to the child, waits up to `grace`, then SIGKILLs its
// group. The exit code or -1.
inline int StopChild(pid_t pid, int signal, std::chrono::milliseconds grace) {
  if (pid <= 0) return -1;
  ::kill(pid, signal);
  return WaitChild(pid, grace);
}

// Whether `pid` is still a live process (a zombie counts as gone: it runs
// nothing and holds no port).
inline bool ProcessRuns(pid_t pid) {
  if (pid <= 0 || ::kill(pid, 0) != 0) return false;
  FILE* f = std::fopen(("/proc/" + std::to_string(pid) + "/stat").c_str(), "r");
  if (f == nullptr) return false;
  char state = '?';
  // "pid (comm) state ...": comm may hold spaces and parentheses; the state
  // follows the last ')'.
  std::string line(512, '\0');
  const size_t n = std::fread(line.data(), 1, line.size() - 1, f);
  std::fclose(f);
  line.resize(n);
  const size_t close = line.rfind(')');
  if (close != std::string::npos && close + 2 < line.size())
    state = line[close + 2];
  return state != 'Z' && state != 'X';
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

#endif  // MESHWAVE_TESTS_PROCESS_CHILD_PROCESS_TESTONLY_H_
