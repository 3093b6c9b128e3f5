#include "meshwave/client/backoff.h"

#include <gtest/gtest.h>

namespace meshwave::client {
namespace {

using std::chrono::milliseconds;

TEST(BackoffTest, DoublesUpToTheCap) {
  RetryPolicy p;
  p.initial_delay = milliseconds(100);
  p.max_delay = milliseconds(1000);
  EXPECT_EQ(BackoffDelay(p, 0), milliseconds(0));
  EXPECT_EQ(BackoffDelay(p, 1), milliseconds(100));
  EXPECT_EQ(BackoffDelay(p, 2), milliseconds(200));
  EXPECT_EQ(BackoffDelay(p, 4), milliseconds(800));
  EXPECT_EQ(BackoffDelay(p, 5), milliseconds(1000));
  EXPECT_EQ(BackoffDelay(p, 1000000),
            milliseconds(1000));  // saturates, no overflow
}

TEST(BackoffTest, MultiplierBelowOneKeepsTheDelayConstant) {
  RetryPolicy p;
  p.initial_delay = milliseconds(50);
  p.multiplier = 0.5;
  EXPECT_EQ(BackoffDelay(p, 3), milliseconds(50));
}

}  // namespace
}  // namespace meshwave::client
