#include "core/edge_key.h"

#include <gtest/gtest.h>

namespace meshwave {
namespace {

TEST(EdgeKeyTest, UndirectedKeyIgnoresDirection) {
  EXPECT_EQ(EdgeKey(3, 7), EdgeKey(7, 3));
  EXPECT_NE(EdgeKey(3, 7), EdgeKey(3, 8));
  EXPECT_EQ(EdgeKey(0xffffffffu, 1), (uint64_t{1} << 32) | 0xffffffffu);
}

TEST(EdgeKeyTest, DirectedKeyKeepsDirectionAndReverses) {
  EXPECT_NE(DirectedEdgeKey(3, 7), DirectedEdgeKey(7, 3));
  EXPECT_EQ(ReversedEdgeKey(DirectedEdgeKey(3, 7)), DirectedEdgeKey(7, 3));
  EXPECT_EQ(ReversedEdgeKey(DirectedEdgeKey(0xffffffffu, 0)), DirectedEdgeKey(0, 0xffffffffu));
  // Sorted directed keys group the edges leaving a vertex.
  EXPECT_LT(DirectedEdgeKey(1, 0xffffffffu), DirectedEdgeKey(2, 0));
}

}  // namespace
}  // namespace meshwave
