// The pacing arithmetic on a simulated clock: the long-run rate is the one
// asked for whatever the message sizes, and idle time is not banked.
#include "token_bucket.h"

#include <gtest/gtest.h>

namespace meshwave::server {
namespace {

using Clock = TokenBucket::Clock;
using std::chrono::milliseconds;

// Sends `sizes` in turn, each as soon as the bucket allows; the time at
// which the last one went out.
Clock::time_point SendAll(TokenBucket& bucket, Clock::time_point t,
                          const std::vector<uint64_t>& sizes) {
  for (uint64_t size : sizes) {
    for (;;) {
      const auto wait = bucket.Take(size, t);
      if (wait == Clock::duration::zero()) break;
      t += wait;
    }
  }
  return t;
}

TEST(TokenBucketTest, FirstMessageGoesAtOnceLargerOnesRunIntoDebt) {
  const Clock::time_point t0{};
  TokenBucket bucket(1000, t0);
  EXPECT_EQ(bucket.Take(5000, t0), Clock::duration::zero());
  // 5000 bytes at 1000 B/s: the next waits 5 s.
  EXPECT_EQ(bucket.Take(10, t0), std::chrono::seconds(5));
  EXPECT_EQ(bucket.Take(10, t0 + std::chrono::seconds(5)),
            Clock::duration::zero());
}

TEST(TokenBucketTest, LongRunRateIsTheRequestedOne) {
  const Clock::time_point t0{};
  TokenBucket bucket(200000, t0);
  std::vector<uint64_t> sizes;
  uint64_t total = 0;
  for (int i = 0; i < 500; ++i) {
    sizes.push_back(37 + (i * 7919) % 4000);
    total += sizes.back();
  }
  const auto end = SendAll(bucket, t0, sizes);
  // Everything but the last message was paid for by the time it left.
  const double seconds = std::chrono::duration<double>(end - t0).count();
  EXPECT_NEAR((static_cast<double>(total - sizes.back())) / seconds, 200000,
              200);
}

TEST(TokenBucketTest, CatchesUpALateTimerWithinTheBurst) {
  const Clock::time_point t0{};
  TokenBucket bucket(1000, t0, milliseconds(200));
  EXPECT_EQ(bucket.Take(100, t0), Clock::duration::zero());
  // Due at 100 ms, woken at 250 ms: 150 bytes of credit, capped at 200.
  const auto late = t0 + milliseconds(250);
  EXPECT_EQ(bucket.Take(100, late), Clock::duration::zero());
  EXPECT_EQ(bucket.Take(100, late), Clock::duration::zero());
  EXPECT_GT(bucket.Take(100, late), Clock::duration::zero());
}

TEST(TokenBucketTest, IdleTimeIsNotBanked) {
  const Clock::time_point t0{};
  TokenBucket bucket(1000, t0);
  const auto later = t0 + std::chrono::seconds(60);
  bucket.DropCredit(later);
  EXPECT_EQ(bucket.Take(500, later), Clock::duration::zero());
  EXPECT_EQ(bucket.Take(1, later), milliseconds(500));
}

}  // namespace
}  // namespace meshwave::server
