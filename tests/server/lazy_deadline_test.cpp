// The lazy deadline on a real io_context: later deadlines cost no timer
// operation until the armed wait fires, an earlier one re-arms at once, it
// fires once per deadline, and never for a finished owner.
#include "lazy_deadline.h"

#include <gtest/gtest.h>

namespace meshwave::server {
namespace {

using Clock = LazyDeadline::Clock;
using std::chrono::milliseconds;

struct Fixture {
  net::io_context ioc;
  std::shared_ptr<int> owner = std::make_shared<int>(0);
  LazyDeadline deadline{ioc.get_executor()};
  int fired = 0;
  Clock::time_point fired_at;
  Fixture() {
    deadline.Bind(owner, [this] {
      ++fired;
      fired_at = Clock::now();
    });
  }
  // Runs `f` on the io_context after `after`.
  void At(milliseconds after, std::function<void()> f) {
    auto t = std::make_shared<net::steady_timer>(ioc, after);
    t->async_wait([t, f = std::move(f)](beast::error_code) { f(); });
  }
};

TEST(LazyDeadlineTest, MovingTheDeadlineLaterArmsNothing) {
  Fixture f;
  const auto start = Clock::now();
  for (int i = 0; i < 1000; ++i) f.deadline.ExpiresAfter(milliseconds(60));
  EXPECT_EQ(f.deadline.arms(), 1u);  // the later deadlines were only recorded
  f.ioc.run();
  EXPECT_EQ(f.fired, 1);
  // The wait armed by the first call may end before the last call's
  // deadline (by as long as the loop took, which a busy machine stretches):
  // then it waits once more for the rest, and only once.
  EXPECT_LE(f.deadline.arms(), 2u);
  EXPECT_GE(f.fired_at - start, milliseconds(60));
}

TEST(LazyDeadlineTest, AWaitThatEndsEarlyWaitsAgainForTheRest) {
  Fixture f;
  const auto start = Clock::now();
  f.deadline.ExpiresAfter(milliseconds(50));
  // Traffic at 30 ms moves the deadline to 80 ms: no re-arm then, one when
  // the first wait ends at 50 ms.
  f.At(milliseconds(30), [&] {
    f.deadline.ExpiresAfter(milliseconds(50));
    EXPECT_EQ(f.deadline.arms(), 1u);
  });
  f.ioc.run();
  EXPECT_EQ(f.fired, 1);
  EXPECT_EQ(f.deadline.arms(), 2u);
  EXPECT_GE(f.fired_at - start, milliseconds(80));
}

TEST(LazyDeadlineTest, AnEarlierDeadlineReArmsAtOnce) {
  Fixture f;
  const auto start = Clock::now();
  f.deadline.ExpiresAfter(std::chrono::seconds(30));  // idle
  f.deadline.ExpiresAfter(milliseconds(40));          // a header's timeout
  f.ioc.run();
  EXPECT_EQ(f.fired, 1);
  EXPECT_EQ(f.deadline.arms(), 2u);
  EXPECT_GE(f.fired_at - start, milliseconds(40));
  EXPECT_LT(f.fired_at - start, std::chrono::seconds(10));
}

TEST(LazyDeadlineTest, NeverAndCancelDoNotFire) {
  Fixture f;
  f.deadline.ExpiresAfter(milliseconds(20));
  f.deadline.ExpiresNever();  // the armed wait fires and finds nothing due
  f.ioc.run();
  EXPECT_EQ(f.fired, 0);
  f.ioc.restart();
  f.deadline.ExpiresAfter(std::chrono::seconds(30));
  f.deadline.Cancel();  // no wait left: run() returns at once
  const auto start = Clock::now();
  f.ioc.run();
  EXPECT_EQ(f.fired, 0);
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(5));
  // Usable again after either.
  f.ioc.restart();
  f.deadline.ExpiresAfter(milliseconds(10));
  f.ioc.run();
  EXPECT_EQ(f.fired, 1);
}

TEST(LazyDeadlineTest, AFinishedOwnerIsNotCalled) {
  Fixture f;
  f.deadline.ExpiresAfter(milliseconds(20));
  f.owner.reset();
  f.ioc.run();
  EXPECT_EQ(f.fired, 0);
}

}  // namespace
}  // namespace meshwave::server
