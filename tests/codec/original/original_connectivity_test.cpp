#include "original/original_connectivity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "meshwave/mesh_io.h"
#include "original/original_connectivity_code.h"
#include "test_data.h"

namespace meshwave::original {
namespace {

// The faces as a multiset up to rotation: each rotated to its smallest
// corner, then sorted.
std::vector<Face> Canonical(std::vector<Face> faces) {
  for (Face& f : faces) f = RotateToSmallest(f);
  std::sort(faces.begin(), faces.end());
  return faces;
}

// Encodes, decodes and checks everything both sides must agree on.
// Returns the payload's size in bytes.
size_t ExpectRoundTrip(uint32_t vertex_count, const std::vector<Face>& faces) {
  Traversal sent;
  auto payload = EncodeConnectivity(vertex_count, faces, &sent);
  EXPECT_TRUE(payload.ok()) << payload.status().ToString();
  if (!payload.ok()) return 0;
  auto got = DecodeConnectivity(*payload, vertex_count, faces.size());
  EXPECT_TRUE(got.ok()) << got.status().ToString();
  if (!got.ok()) return 0;
  EXPECT_EQ(got->faces, sent.faces);
  EXPECT_EQ(got->order, sent.order);
  EXPECT_EQ(Canonical(got->faces), Canonical(faces));
  EXPECT_EQ(got->predictions.size(), got->order.size());
  for (size_t i = 0; i < got->predictions.size() && i < sent.predictions.size(); ++i) {
    const Prediction& p = got->predictions[i];
    const Prediction& q = sent.predictions[i];
    EXPECT_TRUE(p.a == q.a && p.b == q.b && p.c == q.c) << "prediction " << i;
  }
  // The order is a permutation; predictions name earlier vertices only.
  std::vector<uint32_t> position(vertex_count, kNoVertex);
  for (size_t i = 0; i < got->order.size(); ++i) {
    EXPECT_LT(got->order[i], vertex_count);
    if (got->order[i] >= vertex_count) return 0;
    EXPECT_EQ(position[got->order[i]], kNoVertex) << "vertex " << got->order[i] << " twice";
    position[got->order[i]] = static_cast<uint32_t>(i);
  }
  EXPECT_EQ(got->order.size(), vertex_count);
  for (size_t i = 0; i < got->predictions.size(); ++i) {
    const Prediction& p = got->predictions[i];
    for (uint32_t v : {p.a, p.b, p.c}) {
      if (v != kNoVertex) {
        EXPECT_LT(position[v], i) << "prediction of entry " << i;
      }
    }
    // Filled in order: no c without b, no b without a.
    EXPECT_TRUE(p.c == kNoVertex || p.b != kNoVertex);
    EXPECT_TRUE(p.b == kNoVertex || p.a != kNoVertex);
  }
  return payload->size();
}

// A rows x cols grid of vertices, two triangles per cell, row-major ids.
std::vector<Face> Grid(uint32_t rows, uint32_t cols) {
  std::vector<Face> faces;
  for (uint32_t r = 0; r + 1 < rows; ++r) {
    for (uint32_t c = 0; c + 1 < cols; ++c) {
      const uint32_t v = r * cols + c;
      faces.push_back({v, v + 1, v + cols + 1});
      faces.push_back({v, v + cols + 1, v + cols});
    }
  }
  return faces;
}

// A closed UV sphere: `rings` rings of `segments` vertices and two poles.
std::vector<Face> Sphere(uint32_t rings, uint32_t segments, uint32_t* vertex_count) {
  std::vector<Face> faces;
  const uint32_t north = rings * segments, south = north + 1;
  const auto at = [&](uint32_t r, uint32_t s) { return r * segments + s % segments; };
  for (uint32_t s = 0; s < segments; ++s) {
    faces.push_back({north, at(0, s), at(0, s + 1)});
    faces.push_back({south, at(rings - 1, s + 1), at(rings - 1, s)});
    for (uint32_t r = 0; r + 1 < rings; ++r) {
      faces.push_back({at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      faces.push_back({at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  }
  *vertex_count = south + 1;
  return faces;
}

// The same faces over ids permuted at random, in a random face order.
std::vector<Face> Shuffled(uint32_t vertex_count, std::vector<Face> faces, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> id(vertex_count);
  std::iota(id.begin(), id.end(), 0u);
  std::shuffle(id.begin(), id.end(), rng);
  for (Face& f : faces) f = {id[f[0]], id[f[1]], id[f[2]]};
  std::shuffle(faces.begin(), faces.end(), rng);
  return faces;
}

TEST(OriginalConnectivityTest, SampleMeshesRoundTrip) {
  for (const char* name : {"elephant.off", "holes.off"}) {
    SCOPED_TRACE(name);
    auto mesh = ReadMesh(testing::SampleMesh(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    const size_t bytes = ExpectRoundTrip(static_cast<uint32_t>(mesh->positions.size()), mesh->faces);
    EXPECT_GT(bytes, 0u);
  }
}

TEST(OriginalConnectivityTest, GridsAndSpheresRoundTrip) {
  ExpectRoundTrip(4, {{0, 1, 2}});
  ExpectRoundTrip(30 * 20, Grid(30, 20));
  uint32_t n = 0;
  const std::vector<Face> sphere = Sphere(12, 16, &n);
  ExpectRoundTrip(n, sphere);
  ExpectRoundTrip(n, Shuffled(n, sphere, 7));
}

TEST(OriginalConnectivityTest, CoherentIdsCostLessThanShuffledOnes) {
  const uint32_t rows = 40, cols = 40;
  const std::vector<Face> grid = Grid(rows, cols);
  const size_t in_order = ExpectRoundTrip(rows * cols, grid);
  const size_t shuffled = ExpectRoundTrip(rows * cols, Shuffled(rows * cols, grid, 3));
  // Row-major ids on a grid follow from the gate's (a + b - c): nearly
  // free; shuffled ones cost about log2(1600) = 10.6 bits each.
  EXPECT_LT(in_order * 8, rows * cols * 9) << in_order << " bytes in order";
  EXPECT_GT(shuffled * 8, in_order * 8 + rows * cols * 6) << shuffled << " bytes shuffled";
}

TEST(OriginalConnectivityTest, AwkwardFaceSetsRoundTrip) {
  // No faces; only isolated vertices.
  ExpectRoundTrip(0, {});
  ExpectRoundTrip(5, {});
  // An edge in three faces, and in four.
  ExpectRoundTrip(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  ExpectRoundTrip(6, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {1, 0, 5}});
  // Two fans meeting at one vertex (a non-manifold vertex), each closed.
  ExpectRoundTrip(7, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {0, 4, 5}, {0, 5, 6}, {0, 6, 4}});
  // Duplicates: the same face twice, and reversed; repeated three times.
  ExpectRoundTrip(4, {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {1, 2, 0}, {0, 2, 3}});
  // Degenerate faces: a repeated id, all three the same.
  ExpectRoundTrip(4, {{0, 1, 2}, {0, 0, 1}, {3, 3, 3}, {2, 1, 1}});
  // Neighbours oriented against each other; isolated vertices between.
  ExpectRoundTrip(9, {{0, 1, 2}, {1, 2, 3}, {5, 7, 8}, {7, 5, 6}});
  // Several components, faces in no particular order, ids far apart.
  ExpectRoundTrip(1000, {{999, 3, 500}, {10, 11, 12}, {3, 999, 4}, {12, 11, 13}, {0, 1, 2}});
}

TEST(OriginalConnectivityTest, AwkwardCasesTogetherWithAShuffledMesh) {
  uint32_t n = 0;
  const std::vector<Face> sphere = Sphere(6, 8, &n);
  std::vector<Face> faces = Shuffled(n, sphere, 11);
  const uint32_t extra = n + 3;  // n and n + 2 in no face
  faces.push_back(faces[5]);                                // duplicate
  faces.push_back({faces[6][2], faces[6][1], faces[6][0]});  // reversed duplicate
  faces.push_back({faces[7][0], faces[7][0], faces[7][1]});  // degenerate
  faces.push_back({faces[8][0], faces[8][1], n + 1});        // third face on an edge
  ExpectRoundTrip(extra, faces);
}

TEST(OriginalConnectivityTest, RefusesIdsOutOfRange) {
  auto r = EncodeConnectivity(3, {{0, 1, 3}}, nullptr);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
}

TEST(OriginalConnectivityTest, RefusesCountsThatDisagree) {
  const std::vector<Face> grid = Grid(10, 10);
  auto payload = EncodeConnectivity(100, grid, nullptr);
  ASSERT_TRUE(payload.ok());
  ASSERT_TRUE(DecodeConnectivity(*payload, 100, grid.size()).ok());
  for (uint32_t vertices : {0u, 50u, 99u, 101u, 100000u}) {
    auto r = DecodeConnectivity(*payload, vertices, grid.size());
    ASSERT_FALSE(r.ok()) << vertices << " vertices";
    EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  }
  for (uint64_t faces : {uint64_t{0}, uint64_t{1}, grid.size() - 1, grid.size() + 1,
                         uint64_t{1} << 40}) {
    auto r = DecodeConnectivity(*payload, 100, faces);
    ASSERT_FALSE(r.ok()) << faces << " faces";
    EXPECT_EQ(r.status().code(), StatusCode::kParseError);
    EXPECT_NE(r.status().message().find("face"), std::string::npos) << r.status().message();
  }
}

TEST(OriginalConnectivityTest, RefusesTruncatedAndDamagedPayloads) {
  auto mesh = ReadMesh(testing::SampleMesh("holes.off"));
  ASSERT_TRUE(mesh.ok());
  const uint32_t n = static_cast<uint32_t>(mesh->positions.size());
  auto payload = EncodeConnectivity(n, mesh->faces, nullptr);
  ASSERT_TRUE(payload.ok());
  for (size_t keep : {size_t{0}, size_t{1}, payload->size() / 2, payload->size() - 16}) {
    auto r = DecodeConnectivity(payload->substr(0, keep), n, mesh->faces.size());
    ASSERT_FALSE(r.ok()) << keep << " bytes kept";
    EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  }
  // Damage anywhere: refused, never a crash; the few that still decode
  // must describe a valid traversal.
  std::mt19937 rng(5);
  int refused = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::string damaged = *payload;
    damaged[rng() % damaged.size()] ^= static_cast<char>(1 + rng() % 255);
    auto r = DecodeConnectivity(damaged, n, mesh->faces.size());
    if (!r.ok()) {
      ++refused;
      EXPECT_EQ(r.status().code(), StatusCode::kParseError);
      continue;
    }
    EXPECT_EQ(r->order.size(), n);
    EXPECT_EQ(r->faces.size(), mesh->faces.size());
  }
  EXPECT_GT(refused, 40);
}

}  // namespace
}  // namespace meshwave::original
