#include "core/edge_index_table.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>

namespace meshwave {
namespace {

TEST(EdgeIndexTableTest, AnEdgeIsTheSameEitherWayRound) {
  EdgeIndexTable table(4);
  EXPECT_EQ(table.Find(3, 7), nullptr);
  auto [value, inserted] = table.Emplace(7, 3, 11);
  EXPECT_TRUE(inserted);
  EXPECT_EQ(value, 11u);
  auto again = table.Emplace(3, 7, 99);  // present: keeps its value
  EXPECT_FALSE(again.second);
  EXPECT_EQ(again.first, 11u);
  again.first = 12;  // the value is writable in place
  const uint32_t* found = table.Find(7, 3);
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found == nullptr ? 0u : *found, 12u);
  EXPECT_EQ(table.Find(3, 8), nullptr);
  EXPECT_EQ(table.size(), 1u);
}

TEST(EdgeIndexTableTest, GrowsPastItsExpectedSizeAndAgreesWithAMap) {
  // Far more edges than expected, from a small vertex range (collisions
  // and repeated edges), checked against std::map all along.
  std::mt19937 rng(5);
  std::uniform_int_distribution<uint32_t> vertex(0, 3000);
  EdgeIndexTable table(10);
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> reference;
  for (uint32_t i = 0; i < 200000; ++i) {
    uint32_t a = vertex(rng), b = vertex(rng);
    if (a == b) continue;
    auto [value, inserted] = table.Emplace(a, b, i);
    auto [it, fresh] = reference.try_emplace({std::min(a, b), std::max(a, b)}, i);
    ASSERT_EQ(inserted, fresh) << i;
    ASSERT_EQ(value, it->second) << i;
  }
  EXPECT_EQ(table.size(), reference.size());
  for (const auto& [edge, value] : reference) {
    const uint32_t* found = table.Find(edge.second, edge.first);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found == nullptr ? 0u : *found, value);
  }
  EXPECT_EQ(table.Find(3001, 3002), nullptr);
}

}  // namespace
}  // namespace meshwave
