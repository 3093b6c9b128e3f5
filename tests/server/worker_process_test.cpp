// The worker process: a program run with arguments and input, its output
// and exit collected whole (also when it writes more than a pipe holds
// before reading its input), at a lower priority, and its death reported
// in words; and the upload worker's answer read back, errors included.
#include "worker_process.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include "upload_worker.h"

namespace meshwave::server {
namespace {

WorkerOptions Shell() {
  WorkerOptions o;
  o.program = "/bin/sh";
  return o;
}

TEST(WorkerProcessTest, FeedsInputAndCollectsOutputAndExit) {
  // Writes 1 MiB before it reads anything: the caller must drain while
  // it feeds, or both would wait forever.
  auto r = RunWorker({"-c", "head -c 1048576 /dev/zero; wc -c; echo oops >&2; exit 3"},
                     std::string(300000, 'x'), Shell());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->exit_code, 3);
  ASSERT_EQ(r->out.size(), 1048576u + 7u);
  EXPECT_EQ(r->out.substr(1048576), "300000\n");
  EXPECT_EQ(r->err, "oops\n");
}

TEST(WorkerProcessTest, RunsNicerThanItsParent) {
  WorkerOptions o = Shell();
  o.nice = 7;
  errno = 0;
  const int ours = getpriority(PRIO_PROCESS, 0);
  auto r = RunWorker({"-c", "cut -d ' ' -f 19 /proc/self/stat"}, "", o);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->out, std::to_string(std::min(ours + 7, 19)) + "\n");
}

TEST(WorkerProcessTest, ALimitedWorkerThatRunsOutOfMemoryFailsAlone) {
  WorkerOptions o = Shell();
  o.memory_limit_bytes = 64 << 20;
  // sh cannot allocate a 200 MB string within 64 MiB of address space.
  auto r = RunWorker({"-c", "x=$(head -c 200000000 /dev/zero | tr '\\0' a); echo done"}, "", o);
  ASSERT_TRUE(r.ok());
  EXPECT_NE(r->out, "done\n");
}

TEST(WorkerProcessTest, SaysHowAWorkerEnded) {
  auto r = RunWorker({"-c", "kill -9 $$"}, "", Shell());
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->exit_code, -9);
  EXPECT_EQ(DescribeExit(r->exit_code), "was killed by signal 9 (SIGKILL)");
  EXPECT_EQ(DescribeExit(2), "exited with code 2");
  WorkerOptions missing;
  missing.program = "/nonexistent/program";
  auto m = RunWorker({}, "", missing);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->exit_code, 127);
}

TEST(UploadWorkerTest, OutcomesReadBack) {
  IngestResult ok;
  ok.entry.id = "0123456789ab";
  ok.remeshed = true;
  ok.fidelity_db = 84.25;
  auto back = ParseUploadOutcome(FormatUploadOutcome(ok));
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->id, "0123456789ab");
  EXPECT_FALSE(back->already_present);
  EXPECT_TRUE(back->remeshed);
  EXPECT_EQ(back->fidelity_db, 84.25);

  auto error = ParseUploadOutcome(FormatUploadOutcome(
      Result<IngestResult>(ParseError("bad.ply: line 3:\nnot a number"))));
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.status().code(), StatusCode::kParseError);
  EXPECT_EQ(error.status().message(), "bad.ply: line 3: not a number");

  for (std::string_view junk : {"", "id x\n", "error x y\n", "error 99 m\n", "hello\n",
                                "id a\nalready_present 2\nremeshed 0\nfidelity_db 0\n"}) {
    auto r = ParseUploadOutcome(junk);
    ASSERT_FALSE(r.ok()) << junk;
    EXPECT_EQ(r.status().code(), StatusCode::kInternal) << junk;
  }
}

}  // namespace
}  // namespace meshwave::server
