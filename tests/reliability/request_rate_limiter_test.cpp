#include "request_rate_limiter.h"

#include <gtest/gtest.h>

#include <string>

namespace meshwave::server {
namespace {

using std::chrono::milliseconds;

// prefix + i (not `"literal" + std::to_string(i)`: GCC 12's -Wrestrict
// misfires on it, GCC bug 105329).
std::string Client(std::string prefix, int i) {
  prefix += std::to_string(i);
  return prefix;
}

TEST(RequestRateLimiterTest, AllowsTheBurstThenTheRate) {
  RequestRateLimiter limiter(10, 5);
  const auto t0 = RequestRateLimiter::Clock::now();
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.Allow("a", t0)) << i;
  EXPECT_FALSE(limiter.Allow("a", t0));
  EXPECT_TRUE(limiter.Allow("b", t0));  // another client has its own bucket
  EXPECT_FALSE(limiter.Allow("a", t0 + milliseconds(50)));
  EXPECT_TRUE(limiter.Allow("a", t0 + milliseconds(100)));  // 10/s: one per 100 ms
  EXPECT_FALSE(limiter.Allow("a", t0 + milliseconds(150)));
  // Idle credit is capped at the burst.
  int allowed = 0;
  for (int i = 0; i < 20; ++i) allowed += limiter.Allow("a", t0 + std::chrono::seconds(60));
  EXPECT_EQ(allowed, 5);
}

TEST(RequestRateLimiterTest, ZeroRateMeansNoLimit) {
  RequestRateLimiter limiter(0, 0);
  for (int i = 0; i < 1000; ++i) EXPECT_TRUE(limiter.Allow("a"));
  EXPECT_EQ(limiter.clients(), 0u);
}

TEST(RequestRateLimiterTest, TheClientTableStaysBounded) {
  RequestRateLimiter limiter(1, 1, 100);
  const auto t0 = RequestRateLimiter::Clock::now();
  for (int i = 0; i < 10000; ++i) limiter.Allow(Client("10.0.0.", i), t0);
  EXPECT_LE(limiter.clients(), 100u);
  // Clients whose bucket has refilled are forgotten first.
  for (int i = 0; i < 50; ++i) limiter.Allow(Client("x", i), t0 + std::chrono::seconds(5));
  EXPECT_LE(limiter.clients(), 100u);
}

}  // namespace
}  // namespace meshwave::server
