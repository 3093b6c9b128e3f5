#include "meshwave/client/budget.h"

#include <gtest/gtest.h>

#include <cmath>

#include "client_test_stream.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"

namespace meshwave::client {
namespace {

TEST(BudgetTest, ParsesRatesInBitsAndBytes) {
  EXPECT_DOUBLE_EQ(*ParseRate("2Mbit"), 2e6);
  EXPECT_DOUBLE_EQ(*ParseRate("500kbit"), 5e5);
  EXPECT_DOUBLE_EQ(*ParseRate("1.5Gbps"), 1.5e9);
  EXPECT_DOUBLE_EQ(*ParseRate("64000"), 64000);
  EXPECT_DOUBLE_EQ(*ParseRate("1MB/s"), 8e6);
  EXPECT_DOUBLE_EQ(*ParseRate("2KiB/s"), 16384);
}

TEST(BudgetTest, RejectsMalformedRates) {
  for (const char* bad : {"", "Mbit", "0", "0Mbit", "-1Mbit", "2Xbit", "1e3",
                          "2 Mbit/h", "1..2"}) {
    EXPECT_FALSE(ParseRate(bad).ok()) << bad;
  }
}

TEST(BudgetTest, ParsesDurations) {
  EXPECT_DOUBLE_EQ(*ParseDuration("1.5s"), 1.5);
  EXPECT_DOUBLE_EQ(*ParseDuration("200ms"), 0.2);
  EXPECT_DOUBLE_EQ(*ParseDuration("2min"), 120);
  EXPECT_DOUBLE_EQ(*ParseDuration("3"), 3);
  for (const char* bad : {"", "s", "1h", "0s", "-1s"})
    EXPECT_FALSE(ParseDuration(bad).ok()) << bad;
}

TEST(BudgetTest, RateTimesDeadlineGivesBytes) {
  EXPECT_EQ(*RateBudgetBytes(2e6, 1.5), 375000u);
  EXPECT_EQ(*RateBudgetBytes(8, 1), 1u);
  EXPECT_FALSE(RateBudgetBytes(4, 1).ok());  // half a byte
  EXPECT_FALSE(RateBudgetBytes(1e18, 1e6).ok());
}

TEST(BudgetTest, ByteTargetIsTheLocalSelection) {
  const auto& h = testing::ClientTestStream().header;
  const auto order = PacketOrder(h, Progression::kRd);
  for (uint64_t b : {10u, 500u, 3000u, 20000u, 1u << 30}) {
    EXPECT_EQ(TargetCursor(h, order, Budget::Bytes(b)),
              SelectPackets(h, order, b).next_cursor);
  }
  EXPECT_EQ(TargetCursor(h, order, Budget::All()), order.size());
}

TEST(BudgetTest, PsnrTargetIsTheShortestPrefixReachingIt) {
  const auto& h = testing::ClientTestStream().header;
  const auto order = PacketOrder(h, Progression::kQuality);
  const auto curve = EstimatedPsnrCurve(h, order);
  for (double target : {curve[0] - 1, curve[0] + 5, curve[0] + 20}) {
    const size_t k = TargetCursor(h, order, Budget::Psnr(target));
    ASSERT_LE(k, order.size());
    if (k < curve.size() && curve[k] >= target) {
      for (size_t i = 0; i < k; ++i) EXPECT_LT(curve[i], target);
    }
  }
  EXPECT_EQ(TargetCursor(h, order, Budget::Psnr(curve[0] - 1)), 0u);
  EXPECT_EQ(TargetCursor(h, order, Budget::Psnr(1e9)), order.size());
}

}  // namespace
}  // namespace meshwave::client
