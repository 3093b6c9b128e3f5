#include "original/original_positions.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "original/original_positions_model.h"

namespace meshwave::original {
namespace {
// Own namespace: this file shares a unity build with the connectivity test.
namespace positions_test {

struct Case {
  Traversal traversal;
  std::vector<GridPoint> q;
};

// A W x H grid of a smooth height field, coded row by row: each vertex past
// the first row and column from the parallelogram of its left, upper and
// upper-left neighbours; the first row from the vertex to its left; the
// first column from the midpoint of the two above (or the one above).
Case SmoothGrid(uint32_t w, uint32_t h, int precision) {
  Case out;
  const double scale = std::ldexp(1.0, precision) - 1;
  const auto id = [w](uint32_t x, uint32_t y) { return y * w + x; };
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const double u = double(x) / (w - 1), v = double(y) / (h - 1);
      const double z = 0.5 + 0.25 * std::sin(5 * u) * std::cos(4 * v);
      out.q.push_back({uint32_t(u * scale), uint32_t(v * scale), uint32_t(z * scale)});
      Prediction p;
      if (y == 0 && x > 0) {
        p.a = id(x - 1, 0);
      } else if (y > 0 && x == 0) {
        p.a = id(0, y - 1);
        if (y > 1) p.b = id(0, y - 2);  // midpoint of the two above: worse, but exercised
      } else if (y > 0) {
        p = {id(x - 1, y), id(x, y - 1), id(x - 1, y - 1)};
      }
      out.traversal.order.push_back(id(x, y));
      out.traversal.predictions.push_back(p);
    }
  }
  return out;
}

// `n` vertices of random points in [0, 2^precision), in a shuffled order,
// each predicted by a random kind from random earlier vertices.
Case RandomCase(uint32_t n, int precision, uint32_t seed) {
  std::mt19937 rng(seed);
  Case out;
  std::uniform_int_distribution<uint32_t> coordinate(0, (1u << precision) - 1);
  for (uint32_t v = 0; v < n; ++v) out.q.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
  out.traversal.order.resize(n);
  for (uint32_t i = 0; i < n; ++i) out.traversal.order[i] = i;
  std::shuffle(out.traversal.order.begin(), out.traversal.order.end(), rng);
  for (uint32_t i = 0; i < n; ++i) {
    Prediction p;
    const auto earlier = [&] { return out.traversal.order[rng() % i]; };
    switch (i == 0 ? 3 : rng() % 4) {
      case 0: p = {earlier(), earlier(), earlier()}; break;
      case 1: p = {earlier(), earlier()}; break;
      case 2: p = {earlier()}; break;
      default: break;
    }
    out.traversal.predictions.push_back(p);
  }
  return out;
}

// A chain coded vertex after vertex, each from the one before it.
Case Chain(uint32_t n, int precision) {
  Case out;
  const double scale = std::ldexp(1.0, precision) - 1;
  for (uint32_t v = 0; v < n; ++v) {
    const double t = double(v) / n;
    out.q.push_back({uint32_t(t * scale), uint32_t((0.5 + 0.5 * std::sin(9 * t)) * scale),
                     uint32_t((0.5 + 0.5 * std::cos(7 * t)) * scale)});
    out.traversal.order.push_back(v);
    out.traversal.predictions.push_back({});
  }
  return out;
}

uint32_t MaxCoordinate(const std::vector<GridPoint>& q) {
  uint32_t m = 0;
  for (const GridPoint& p : q) m = std::max({m, p[0], p[1], p[2]});
  return m;
}

// Decodes every payload in turn, checking after each that every point lies
// in the cell its bits leave it in, and exactness at the end.
void ExpectRoundTrip(const Case& c, int shift) {
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, shift);
  ASSERT_EQ(payloads.size(), size_t(shift + 1));
  PositionsDecoder decoder(c.traversal, shift, MaxCoordinate(c.q));
  EXPECT_TRUE(decoder.GridPositions().empty());
  for (int k = 0; k <= shift; ++k) {
    ASSERT_TRUE(decoder.Add(k, payloads[k]).ok()) << "payload " << k;
    EXPECT_EQ(decoder.held(), k + 1);
    const auto positions = decoder.GridPositions();
    ASSERT_EQ(positions.size(), c.q.size());
    const double half_cell = ((1u << (shift - k)) - 1) / 2.0;
    for (size_t v = 0; v < c.q.size(); ++v) {
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(std::abs(positions[v][a] - c.q[v][a]), half_cell)
            << "vertex " << v << " payload " << k;
        if (k == shift) {
          ASSERT_EQ(positions[v][a], double(c.q[v][a]));
        }
      }
    }
  }
}

TEST(OriginalPositionsTest, SmoothGridRoundTripsThroughEveryPayload) {
  const Case c = SmoothGrid(24, 17, 14);
  for (int shift : {0, 1, 4}) ExpectRoundTrip(c, shift);
}

TEST(OriginalPositionsTest, RandomTraversalOfEveryKindRoundTrips) {
  const Case c = RandomCase(500, 20, 7);
  int kinds[kPredictionKinds] = {};
  for (const Prediction& p : c.traversal.predictions) ++kinds[int(KindOf(p))];
  for (int count : kinds) EXPECT_GT(count, 50);
  for (int shift : {0, 3, kMaxShift}) ExpectRoundTrip(c, shift);
}

TEST(OriginalPositionsTest, ChainOfPreviousVerticesRoundTrips) {
  for (int shift : {0, 2}) ExpectRoundTrip(Chain(300, 16), shift);
}

TEST(OriginalPositionsTest, ExtremeCoordinatesRoundTrip) {
  // Parallelograms that leave the grid on both sides are clamped alike.
  Case c = RandomCase(200, 1, 3);
  for (GridPoint& p : c.q) {
    for (uint32_t& x : p) x = x ? kMaxGridCoordinate : 0;
  }
  for (int shift : {0, 5}) ExpectRoundTrip(c, shift);
  Case one;
  one.q = {{kMaxGridCoordinate, 0, 12345}};
  one.traversal.order = {0};
  one.traversal.predictions = {{}};
  ExpectRoundTrip(one, 2);
}

TEST(OriginalPositionsTest, ParallelogramsCostLessThanPreviousVertices) {
  // The predictions are used: the same smooth grid coded as a chain costs
  // several times more.
  Case grid = SmoothGrid(40, 40, 14);
  Case chain = grid;
  for (Prediction& p : chain.traversal.predictions) p = {};
  const size_t grid_bytes = EncodePositions(grid.traversal, grid.q, 0)[0].size();
  const size_t chain_bytes = EncodePositions(chain.traversal, chain.q, 0)[0].size();
  EXPECT_LT(grid_bytes * 2, chain_bytes);
}

TEST(OriginalPositionsTest, RefinementPlanesCostAboutOneBitPerCoordinate) {
  const Case c = RandomCase(2000, 16, 11);
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 3);
  for (int k = 1; k <= 3; ++k) {
    EXPECT_NEAR(payloads[k].size() * 8.0 / (3 * c.q.size()), 1.0, 0.02) << "plane " << k;
  }
}

TEST(OriginalPositionsTest, RefinementBitsOfASmoothSurfaceCostLessThanOneBit) {
  // The contexts use the finer prediction: on an exact smooth field most
  // low bits follow from the neighbours.
  const Case c = SmoothGrid(40, 40, 12);
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 6);
  EXPECT_LT(payloads[1].size() * 8.0 / (3 * c.q.size()), 0.7);
}

TEST(OriginalPositionsTest, RefusesPayloadsOutOfTurnLeavingThePointsHeld) {
  const Case c = SmoothGrid(8, 8, 12);
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 2);
  PositionsDecoder decoder(c.traversal, 2, MaxCoordinate(c.q));
  EXPECT_EQ(decoder.Add(1, payloads[1]).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.held(), 0);
  ASSERT_TRUE(decoder.Add(0, payloads[0]).ok());
  const auto before = decoder.GridPositions();
  EXPECT_EQ(decoder.Add(0, payloads[0]).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.Add(2, payloads[2]).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.held(), 1);
  EXPECT_EQ(decoder.GridPositions(), before);
  ASSERT_TRUE(decoder.Add(1, payloads[1]).ok());
  ASSERT_TRUE(decoder.Add(2, payloads[2]).ok());
  EXPECT_EQ(decoder.Add(3, payloads[2]).code(), StatusCode::kInvalidArgument);
}

TEST(OriginalPositionsTest, RefusesTruncatedPayloads) {
  const Case c = SmoothGrid(30, 30, 16);
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 1);
  for (size_t keep : {size_t{0}, payloads[0].size() / 2, payloads[0].size() - 12}) {
    PositionsDecoder decoder(c.traversal, 1, MaxCoordinate(c.q));
    EXPECT_EQ(decoder.Add(0, payloads[0].substr(0, keep)).code(), StatusCode::kParseError)
        << keep << " of " << payloads[0].size() << " bytes";
    EXPECT_EQ(decoder.held(), 0);
    EXPECT_TRUE(decoder.GridPositions().empty());
  }
  PositionsDecoder decoder(c.traversal, 1, MaxCoordinate(c.q));
  ASSERT_TRUE(decoder.Add(0, payloads[0]).ok());
  const auto coarse = decoder.GridPositions();
  EXPECT_EQ(decoder.Add(1, payloads[1].substr(0, payloads[1].size() / 2)).code(),
            StatusCode::kParseError);
  EXPECT_EQ(decoder.held(), 1);
  EXPECT_EQ(decoder.GridPositions(), coarse);
  EXPECT_TRUE(decoder.Add(1, payloads[1]).ok());
}

TEST(OriginalPositionsTest, RefusesGarbage) {
  const Case c = SmoothGrid(20, 20, 12);
  std::mt19937 rng(5);
  std::string garbage(300, '\0');
  for (char& b : garbage) b = char(rng());
  PositionsDecoder decoder(c.traversal, 0, MaxCoordinate(c.q));
  EXPECT_EQ(decoder.Add(0, garbage).code(), StatusCode::kParseError);
  EXPECT_EQ(decoder.held(), 0);
}

TEST(OriginalPositionsTest, RefusesCoordinatesBeyondTheGridExtent) {
  Case c = SmoothGrid(10, 10, 12);
  const uint32_t max = MaxCoordinate(c.q);
  // Coarse: a point beyond the extent at payload 0's precision.
  c.q[37][1] = max + 8;
  std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 2);
  PositionsDecoder coarse(c.traversal, 2, max);
  EXPECT_EQ(coarse.Add(0, payloads[0]).code(), StatusCode::kParseError);
  // Refinement: with the extent's two low bits 0, a point ...10 above it
  // has its coarse part within the extent and leaves it with its next bit.
  const uint32_t extent = max & ~3u;
  c.q[37][1] = extent | 2;
  payloads = EncodePositions(c.traversal, c.q, 2);
  PositionsDecoder fine(c.traversal, 2, extent);
  ASSERT_TRUE(fine.Add(0, payloads[0]).ok());
  const auto held = fine.GridPositions();
  EXPECT_EQ(fine.Add(1, payloads[1]).code(), StatusCode::kParseError);
  EXPECT_EQ(fine.GridPositions(), held);
}

TEST(OriginalPositionsTest, RefusesTraversalsNamingUnknownVertices) {
  Case c = SmoothGrid(6, 6, 10);
  const std::vector<std::string> payloads = EncodePositions(c.traversal, c.q, 0);
  c.traversal.predictions[20].c = 36;
  PositionsDecoder decoder(c.traversal, 0, MaxCoordinate(c.q));
  EXPECT_EQ(decoder.Add(0, payloads[0]).code(), StatusCode::kInvalidArgument);
  c.traversal.predictions.pop_back();
  EXPECT_EQ(decoder.Add(0, payloads[0]).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.held(), 0);
}

}  // namespace positions_test
}  // namespace
}  // namespace meshwave::original
