#include "core/hilbert_order.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <vector>

namespace meshwave {
namespace {

// Every cell of a 2^k grid once, consecutive cells face neighbours: the
// curve's defining property, at the coarse scales the precincts use.
TEST(HilbertOrderTest, ConsecutiveCellsOfAGridTouch) {
  for (int k : {1, 2, 3, 4}) {
    const int n = 1 << k;
    std::vector<std::array<int64_t, 3>> cells;
    for (int x = 0; x < n; ++x) {
      for (int y = 0; y < n; ++y) {
        for (int z = 0; z < n; ++z) cells.push_back({x, y, z});
      }
    }
    const std::vector<uint32_t> order = HilbertOrder(cells);
    ASSERT_EQ(order.size(), cells.size());
    std::set<uint32_t> seen(order.begin(), order.end());
    EXPECT_EQ(seen.size(), cells.size());
    for (size_t i = 1; i < order.size(); ++i) {
      const auto& a = cells[order[i - 1]];
      const auto& b = cells[order[i]];
      const int64_t step = std::llabs(a[0] - b[0]) + std::llabs(a[1] - b[1]) + std::llabs(a[2] - b[2]);
      ASSERT_EQ(step, 1) << "k " << k << " at " << i;
    }
  }
}

TEST(HilbertOrderTest, IndicesAreABijectionOnTheTopBits) {
  std::set<uint64_t> seen;
  for (uint32_t x = 0; x < 8; ++x) {
    for (uint32_t y = 0; y < 8; ++y) {
      for (uint32_t z = 0; z < 8; ++z) {
        // The cell of the 8^3 grid is the index's top 9 bits.
        seen.insert(HilbertIndex({x << 18, y << 18, z << 18}) >> 54);
      }
    }
  }
  EXPECT_EQ(seen.size(), 512u);
  EXPECT_EQ(*seen.rbegin(), 511u);
}

TEST(HilbertOrderTest, TiesKeepTheirOrderAndNoPointsIsFine) {
  const std::vector<std::array<int64_t, 3>> same(5, {7, -3, 2});
  EXPECT_EQ(HilbertOrder(same), (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(HilbertOrder(std::span<const std::array<int64_t, 3>>{}).empty());
}

}  // namespace
}  // namespace meshwave
