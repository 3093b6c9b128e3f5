#include "core/work_ahead.h"

#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace meshwave {
namespace {

TEST(WorkAheadTest, RunsEveryStepInOrderOnAnotherThread) {
  std::mutex mutex;
  std::condition_variable cv;
  std::vector<size_t> done;
  std::vector<std::thread::id> ran_on;
  WorkAhead ahead;
  ahead.Start(5, [&](size_t i) {
    const std::lock_guard lock(mutex);
    done.push_back(i);
    ran_on.push_back(std::this_thread::get_id());
    cv.notify_all();
  });
  std::unique_lock lock(mutex);
  cv.wait(lock, [&] { return done.size() == 5; });
  EXPECT_EQ(done, (std::vector<size_t>{0, 1, 2, 3, 4}));
  for (const auto& id : ran_on) EXPECT_NE(id, std::this_thread::get_id());
}

TEST(WorkAheadTest, StoppedItFinishesTheStepUnderWayAndStartsNoOther) {
  std::atomic<int> started = 0, finished = 0;
  std::atomic<bool> in_step = false;
  WorkAhead ahead;
  ahead.Start(100, [&](size_t) {
    ++started;
    in_step = true;
    while (!ahead.stopping()) std::this_thread::yield();
    ++finished;
  });
  while (!in_step) std::this_thread::yield();
  ahead.Stop();  // waits for the step under way, which waits for the stop
  EXPECT_EQ(started.load(), 1);
  EXPECT_EQ(finished.load(), 1);
}

TEST(WorkAheadTest, AStepThatThrowsEndsTheRun) {
  std::atomic<int> ran = 0;
  {
    WorkAhead ahead;
    ahead.Start(10, [&](size_t i) {
      ++ran;
      if (i == 2) throw std::runtime_error("no memory");
    });
  }  // joins; the error stays on the thread
  EXPECT_LE(ran.load(), 3);
}

TEST(WorkAheadTest, NeverStartedItIsDestroyedQuietly) {
  WorkAhead ahead;
  ahead.Stop();
  ahead.Stop();
}

}  // namespace
}  // namespace meshwave
