// The client's retry loop (client/src/retry.h) and blocking run
// (client/src/run_to_completion.h) on a bare io_context: I/O errors are
// tried again after a backoff until max_attempts tries in a row make no
// progress, progress starts the count again, other errors end it at once;
// a blocking run ends with its task, not when the io_context runs dry.
#include "retry.h"

#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <vector>

#include "run_to_completion.h"

namespace meshwave::client {
namespace {

RetryPolicy Quick(int attempts) {
  RetryPolicy p;
  p.max_attempts = attempts;
  p.initial_delay = std::chrono::milliseconds(1);
  p.max_delay = std::chrono::milliseconds(2);
  return p;
}

// Runs RetryWithBackoff over a scripted list of step results; `progress`
// tells which tries (by index) made progress.
struct Script {
  std::vector<Result<bool>> results;
  std::vector<bool> progress;
  size_t tries = 0;
  int marks = 0;

  Status Run(const RetryPolicy& policy, int& retries) {
    net::io_context io(1);
    return RunToCompletion(
        io, RetryWithBackoff(
                io.get_executor(), policy, retries,
                [this]() -> net::awaitable<Result<bool>> {
                  const size_t k = tries++;
                  if (k < progress.size() && progress[k]) ++marks;
                  co_return k < results.size() ? results[k] : Result<bool>(true);
                },
                [this] { return marks; }));
  }
};

TEST(RetryTest, RetriesIoErrorsUntilTheStepIsDone) {
  Script s{{IoError("reset"), IoError("reset"), false, true}, {}};
  int retries = 0;
  EXPECT_TRUE(s.Run(Quick(3), retries).ok());
  EXPECT_EQ(s.tries, 4u);
  EXPECT_EQ(retries, 2);
}

TEST(RetryTest, GivesUpAfterMaxAttemptsWithoutProgress) {
  Script s{{IoError("a"), IoError("b"), IoError("c"), IoError("d")}, {}};
  int retries = 0;
  const Status status = s.Run(Quick(3), retries);
  EXPECT_EQ(status.code(), StatusCode::kIoError);
  EXPECT_NE(status.message().find("gave up after 3 attempts"), std::string::npos)
      << status.ToString();
  EXPECT_EQ(s.tries, 3u);
  EXPECT_EQ(retries, 2);
}

TEST(RetryTest, ProgressStartsTheCountAgain) {
  // Three failures in a row would give up at the third; it made progress.
  Script s{{IoError("a"), IoError("b"), IoError("c"), IoError("d"), true},
           {false, false, true, false, false}};
  int retries = 0;
  EXPECT_TRUE(s.Run(Quick(3), retries).ok());
  EXPECT_EQ(s.tries, 5u);
  EXPECT_EQ(retries, 4);
}

TEST(RetryTest, OtherErrorsEndTheLoopAtOnce) {
  Script s{{IoError("a"), ParseError("the server sent garbage")}, {}};
  int retries = 0;
  const Status status = s.Run(Quick(5), retries);
  EXPECT_EQ(status.code(), StatusCode::kParseError);
  EXPECT_EQ(s.tries, 2u);
  EXPECT_EQ(retries, 1);
}

TEST(RunToCompletionTest, EndsWithTheTaskNotWhenTheIoContextRunsDry) {
  net::io_context io(1);
  // A timer far in the future keeps the io_context busy, as a WebSocket's
  // idle timer does between fetches.
  net::steady_timer idle(io, std::chrono::hours(1));
  idle.async_wait([](auto) {});
  auto task = []() -> net::awaitable<Status> { co_return ParseError("done"); };
  EXPECT_EQ(RunToCompletion(io, task()).code(), StatusCode::kParseError);
  // The io_context can run the next task.
  auto ok = []() -> net::awaitable<Status> { co_return Status::Ok(); };
  EXPECT_TRUE(RunToCompletion(io, ok()).ok());
}

TEST(RunToCompletionTest, AnExceptionBecomesAnInternalError) {
  net::io_context io(1);
  auto task = []() -> net::awaitable<Status> {
    throw std::runtime_error("bug");
    co_return Status::Ok();
  };
  const Status s = RunToCompletion(io, task());
  EXPECT_EQ(s.code(), StatusCode::kInternal);
  EXPECT_EQ(s.message(), "bug");
}

}  // namespace
}  // namespace meshwave::client
