#include "worker_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace meshwave::server {
namespace {

// Closes its descriptors on scope exit.
struct Pipe {
  int fd[2] = {-1, -1};
  ~Pipe() {
    for (int f : fd) {
      if (f >= 0) close(f);
    }
  }
  Status Open() {
    if (pipe2(fd, O_CLOEXEC) != 0) return IoError(std::string("pipe: ") + std::strerror(errno));
    return Status::Ok();
  }
  void CloseEnd(int i) {
    if (fd[i] >= 0) close(fd[i]);
    fd[i] = -1;
  }
};

}  // namespace

std::string DescribeExit(int exit_code) {
  if (exit_code >= 0) return "exited with code " + std::to_string(exit_code);
  const int signal = -exit_code;
  const char* name = sigabbrev_np(signal);
  return "was killed by signal " + std::to_string(signal) +
         (name ? std::string(" (SIG") + name + ")" : std::string());
}

Result<WorkerResult> RunWorker(const std::vector<std::string>& args, std::string_view input,
                               const WorkerOptions& options) {
  // Everything the child needs is made before fork: after it, only
  // async-signal-safe calls until exec (the server has other threads).
  std::vector<std::string> argv_strings;
  argv_strings.push_back("meshwave-server");
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const std::string program = options.program.empty() ? "/proc/self/exe" : options.program;

  Pipe in, out, err;
  MW_RETURN_IF_ERROR(in.Open());
  MW_RETURN_IF_ERROR(out.Open());
  MW_RETURN_IF_ERROR(err.Open());
  const pid_t pid = fork();
  if (pid < 0) return IoError(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);  // the server died before prctl
    dup2(in.fd[0], STDIN_FILENO);
    dup2(out.fd[1], STDOUT_FILENO);
    dup2(err.fd[1], STDERR_FILENO);
    if (options.nice > 0) (void)!nice(options.nice);
    if (options.memory_limit_bytes > 0) {
      const rlimit limit{options.memory_limit_bytes, options.memory_limit_bytes};
      setrlimit(RLIMIT_AS, &limit);
    }
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  in.CloseEnd(0);
  out.CloseEnd(1);
  err.CloseEnd(1);
  // Feed stdin and drain stdout and stderr together: a child that writes
  // a lot before reading all of its input must not deadlock with us.
  WorkerResult result;
  size_t written = 0;
  if (input.empty()) in.CloseEnd(1);
  // A child that exits before reading all its input must not kill the
  // server with SIGPIPE (process-wide; sockets already send with
  // MSG_NOSIGNAL).
  signal(SIGPIPE, SIG_IGN);
  while (out.fd[0] >= 0 || err.fd[0] >= 0) {
    pollfd fds[3];
    int n = 0;
    if (in.fd[1] >= 0) fds[n++] = {in.fd[1], POLLOUT, 0};
    if (out.fd[0] >= 0) fds[n++] = {out.fd[0], POLLIN, 0};
    if (err.fd[0] >= 0) fds[n++] = {err.fd[0], POLLIN, 0};
    if (poll(fds, static_cast<nfds_t>(n), -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < n; ++i) {
      if (fds[i].revents == 0) continue;
      if (fds[i].fd == in.fd[1]) {
        const ssize_t w = write(in.fd[1], input.data() + written,
                                std::min<size_t>(input.size() - written, 1 << 16));
        if (w > 0) written += static_cast<size_t>(w);
        if (w < 0 || written == input.size()) in.CloseEnd(1);
        continue;
      }
      char buffer[1 << 14];
      const ssize_t r = read(fds[i].fd, buffer, sizeof buffer);
      const bool is_out = fds[i].fd == out.fd[0];
      if (r > 0) {
        (is_out ? result.out : result.err).append(buffer, static_cast<size_t>(r));
      } else if (r == 0 || errno != EINTR) {
        (is_out ? out : err).CloseEnd(0);
      }
    }
  }
  in.CloseEnd(1);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
  return result;
}

}  // namespace meshwave::server
