#include "semiregular/vertex_rings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace meshwave {
namespace {

// A fan of `n` triangles around vertex 0 over rim vertices 1..n, closed
// (a cone) or open (its last triangle left out).
std::vector<Face> Fan(uint32_t n, bool closed) {
  std::vector<Face> faces;
  const uint32_t count = closed ? n : n - 1;
  for (uint32_t i = 0; i < count; ++i) faces.push_back({0, 1 + i, 1 + (i + 1) % n});
  return faces;
}

std::vector<uint32_t> RingOf(const VertexRings& rings, uint32_t v) {
  const auto r = rings.Ring(v);
  return {r.begin(), r.end()};
}

// Fans of 6 faces take the linear search, of 20 the sorted one.
class VertexRingsFanTest : public ::testing::TestWithParam<uint32_t> {};

TEST_P(VertexRingsFanTest, ClosedFanIsCounterClockwiseFromItsSmallestNeighbour) {
  const uint32_t n = GetParam();
  std::vector<Face> faces = Fan(n, true);
  // Closing the cone's bottom would add faces to the rim; vertex 0 alone is
  // what is checked, so the rim stays open.
  std::mt19937 rng(n);
  std::shuffle(faces.begin(), faces.end(), rng);
  auto rings = VertexRings::Build(n + 1, faces);
  ASSERT_TRUE(rings.ok()) << rings.status().ToString();
  std::vector<uint32_t> expected;
  for (uint32_t i = 0; i < n; ++i) expected.push_back(1 + i);
  EXPECT_EQ(RingOf(*rings, 0), expected);
  EXPECT_FALSE(rings->IsBoundary(0));
  EXPECT_EQ(rings->Valence(0), n);
  // A rim vertex: two faces, so three neighbours, from the boundary on.
  EXPECT_TRUE(rings->IsBoundary(1));
  EXPECT_EQ(RingOf(*rings, 1), (std::vector<uint32_t>{2, 0, n}));
}

TEST_P(VertexRingsFanTest, OpenFanStartsAtTheBoundary) {
  const uint32_t n = GetParam();
  std::vector<Face> faces = Fan(n, false);
  std::mt19937 rng(n + 1);
  std::shuffle(faces.begin(), faces.end(), rng);
  auto rings = VertexRings::Build(n + 1, faces);
  ASSERT_TRUE(rings.ok()) << rings.status().ToString();
  std::vector<uint32_t> expected;
  for (uint32_t i = 0; i < n; ++i) expected.push_back(1 + i);
  EXPECT_EQ(RingOf(*rings, 0), expected);
  EXPECT_TRUE(rings->IsBoundary(0));
}

TEST_P(VertexRingsFanTest, EdgeUsedTwiceInOneDirectionIsNotManifold) {
  const uint32_t n = GetParam();
  std::vector<Face> faces = Fan(n, true);
  faces.push_back({0, 1, 2});  // edge 0 -> 1 a second time
  auto rings = VertexRings::Build(n + 1, faces);
  ASSERT_FALSE(rings.ok());
  EXPECT_EQ(rings.status().code(), StatusCode::kNotManifold);
  EXPECT_NE(rings.status().message().find("edge (0, 1)"), std::string::npos)
      << rings.status().ToString();
}

TEST_P(VertexRingsFanTest, TwoFansAtOneVertexAreNotManifold) {
  const uint32_t n = GetParam();
  // Two open fans around vertex 0 sharing nothing else.
  std::vector<Face> faces = Fan(n, false);
  for (uint32_t i = 0; i + 1 < n; ++i) faces.push_back({0, n + 1 + i, n + 2 + i});
  auto rings = VertexRings::Build(2 * n + 1, faces);
  ASSERT_FALSE(rings.ok());
  EXPECT_EQ(rings.status().code(), StatusCode::kNotManifold);
  EXPECT_NE(rings.status().message().find("vertex 0 joins several fans"), std::string::npos)
      << rings.status().ToString();
}

INSTANTIATE_TEST_SUITE_P(LinearAndSorted, VertexRingsFanTest, ::testing::Values(6u, 20u));

TEST(VertexRingsTest, BadIndicesAreRefused) {
  EXPECT_EQ(VertexRings::Build(3, std::vector<Face>{{0, 1, 3}}).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(VertexRings::Build(3, std::vector<Face>{{0, 1, 1}}).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(VertexRings::Build(4, std::vector<Face>{{0, 1, 2}}).status().code(),
            StatusCode::kInvalidArgument);  // vertex 3 unused
}

}  // namespace
}  // namespace meshwave
