// Heavy work off the serving process: an upload's ingest or a background
// re-encode runs as a child process of meshwave-server (its own binary,
// with a subcommand), at a lower CPU priority and optionally under a
// memory limit, so that serving keeps its throughput and a mesh that needs
// more memory than allowed fails alone instead of taking the server down.
// The child dies with the server.
#ifndef MESHWAVE_SERVER_WORKER_PROCESS_H_
#define MESHWAVE_SERVER_WORKER_PROCESS_H_

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::server {

struct WorkerOptions {
  std::string program;               // empty: this program (/proc/self/exe)
  int nice = 10;                     // added to the server's niceness (0-19)
  uint64_t memory_limit_bytes = 0;   // address space (RLIMIT_AS); 0: none
};

struct WorkerResult {
  int exit_code = 0;    // -N: killed by signal N
  std::string out;      // its standard output
  std::string err;      // its standard error
};

// Runs options.program (this program by default) with `args`, writes `input` to its
// standard input, and collects its standard output and error until it
// exits. Blocks the calling thread. IoError when it cannot be started.
Result<WorkerResult> RunWorker(const std::vector<std::string>& args, std::string_view input,
                               const WorkerOptions& options);

// "exited with code 3", "was killed by signal 9 (SIGKILL)".
std::string DescribeExit(int exit_code);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_WORKER_PROCESS_H_
