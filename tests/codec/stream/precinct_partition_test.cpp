#include "stream/precinct_partition.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <set>
#include <vector>

#include "codec/hierarchy_on_grid_testonly.h"
#include "codec/test_meshes.h"
#include "semiregular/base_face_of.h"

namespace meshwave {
namespace {

// A torus of 24 x 16 quads (768 base faces) subdivided 4 times: enough
// coefficients per subband for many precincts, none on a boundary.
using TorusFixture = testing::HierarchyOnGrid;

TorusFixture MakeTorus() {
  return testing::BuildHierarchyOnGrid(testing::Torus(24, 16), 4, Vec3::Constant(4096));
}

std::vector<uint64_t> CoefficientsPerPrecinct(const SemiRegularHierarchy& h,
                                              const PrecinctPartition& p, int j) {
  std::vector<uint64_t> n(p.count(j), 0);
  for (uint32_t q : CoefficientPrecincts(h, p, j)) ++n[q];
  return n;
}

TEST(PrecinctPartitionTest, EveryBaseFaceIsInOnePrecinctOfEachSubband) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 2000);
  const uint32_t faces = static_cast<uint32_t>(f.h->faces(0).size());
  std::vector<uint32_t> sorted = p.face_order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<uint32_t> all(faces);
  std::iota(all.begin(), all.end(), 0u);
  EXPECT_EQ(sorted, all);  // the order is a permutation
  ASSERT_EQ(p.levels(), 4);
  for (int j = 0; j < 4; ++j) {
    const auto& b = p.bounds[static_cast<size_t>(j)];
    ASSERT_GE(b.size(), 2u);
    EXPECT_EQ(b.front(), 0u);
    EXPECT_EQ(b.back(), faces);
    EXPECT_TRUE(std::is_sorted(b.begin(), b.end()));
    EXPECT_EQ(std::adjacent_find(b.begin(), b.end()), b.end()) << "an empty precinct";
  }
}

// Each subband's precincts split the coarser subband's: every cut of
// subband j - 1 is a cut of subband j.
TEST(PrecinctPartitionTest, FinerSubbandsSplitTheCoarserOnesPrecincts) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 2000);
  for (int j = 1; j < 4; ++j) {
    const std::set<uint32_t> fine(p.bounds[j].begin(), p.bounds[j].end());
    for (uint32_t cut : p.bounds[j - 1]) EXPECT_TRUE(fine.count(cut)) << "j " << j;
    EXPECT_GE(p.count(j), p.count(j - 1));
  }
}

// At least the minimum (save where a whole coarser precinct holds fewer),
// and below 1.5 times it plus one base face's share; the count follows the
// subband's size, 4 times more coefficients per level.
TEST(PrecinctPartitionTest, PrecinctsHoldAboutTheAskedNumberOfCoefficients) {
  const TorusFixture f = MakeTorus();
  const uint32_t least = 2000;
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, least);
  const double per_face_finest = static_cast<double>(f.h->subband_size(3)) /
                                 static_cast<double>(f.h->faces(0).size());
  for (int j = 0; j < 4; ++j) {
    const auto n = CoefficientsPerPrecinct(*f.h, p, j);
    const uint64_t total = std::accumulate(n.begin(), n.end(), uint64_t{0});
    EXPECT_EQ(total, f.h->subband_size(j));
    if (total < least) {
      EXPECT_EQ(p.count(j), 1u) << "j " << j;
      continue;
    }
    for (size_t q = 0; q < n.size(); ++q) {
      EXPECT_GE(n[q], least / 2) << "j " << j << " precinct " << q;
      EXPECT_LT(static_cast<double>(n[q]), 1.5 * least + 2 * per_face_finest)
          << "j " << j << " precinct " << q;
    }
  }
  // 768 base faces: d^3 has 768 * 96 = 73,728 coefficients, about 37 runs
  // of 2,000 (between 73,728 / 3,192 = 24 and 73,728 / 1,000 = 73 by the
  // bounds above); d^0 (1,152) stays whole.
  EXPECT_EQ(p.count(0), 1u);
  EXPECT_GE(p.count(3), 24u);
  EXPECT_LE(p.count(3), 40u);
}

// A precinct is compact: its base faces' centroids lie in a box far smaller
// than the mesh (a run of the Morton order stays in few octree cells).
TEST(PrecinctPartitionTest, PrecinctsAreSpatiallyCompact) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 2000);
  const auto& faces = f.h->faces(0);
  auto centroid = [&](uint32_t face) {
    Vec3 c = Vec3::Zero();
    for (uint32_t v : faces[face]) {
      c += Vec3(static_cast<double>(f.grid[v][0]), static_cast<double>(f.grid[v][1]),
                static_cast<double>(f.grid[v][2]));
    }
    return Vec3(c / 3);
  };
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (uint32_t face = 0; face < faces.size(); ++face) {
    lo = lo.cwiseMin(centroid(face));
    hi = hi.cwiseMax(centroid(face));
  }
  const double mesh_diagonal = (hi - lo).norm();
  const int j = 3;
  double mean = 0;
  for (uint32_t q = 0; q < p.count(j); ++q) {
    Vec3 a = Vec3::Constant(1e300), b = Vec3::Constant(-1e300);
    for (uint32_t i = p.bounds[j][q]; i < p.bounds[j][q + 1]; ++i) {
      a = a.cwiseMin(centroid(p.face_order[i]));
      b = b.cwiseMax(centroid(p.face_order[i]));
    }
    mean += (b - a).norm() / mesh_diagonal;
  }
  mean /= p.count(j);
  std::printf("%u precincts of d^3, mean box diagonal %.3f of the mesh's\n", p.count(j), mean);
  // 37 precincts of a torus: a round patch of 1/37 of its surface would
  // span about 0.16 of the diagonal; random sets of its faces span nearly
  // all of it. Morton runs measure 0.29 (a Hilbert order would be tighter).
  EXPECT_LT(mean, 0.35) << "mean precinct box diagonal over the mesh's";
}

TEST(PrecinctPartitionTest, CoefficientsGoToTheirBaseFacesPrecinct) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 500);
  for (int j = 0; j < 4; ++j) {
    const auto of_face = p.FacePrecincts(j);
    const auto of_coefficient = CoefficientPrecincts(*f.h, p, j);
    ASSERT_EQ(of_coefficient.size(), f.h->subband_size(j));
    for (uint32_t k = 0; k < of_coefficient.size(); ++k) {
      ASSERT_EQ(of_coefficient[k], of_face[BaseFaceOf(*f.h, j, k)]) << j << " " << k;
    }
  }
}

// Asking for more than the whole mesh holds gives one precinct per subband.
TEST(PrecinctPartitionTest, ASmallMeshIsOnePrecinct) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 1u << 30);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(p.count(j), 1u);
}

// Parent(j, p): the precinct of subband j - 1 whose faces include p's.
TEST(PrecinctPartitionTest, AParentIsThePrecinctAboveHoldingTheFaces) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 500);
  const auto parents = p.ParentsPerSubband();
  ASSERT_EQ(parents.size(), 4u);
  EXPECT_TRUE(parents[0].empty());
  int several = 0;
  for (int j = 1; j < 4; ++j) {
    const std::vector<uint32_t> above = p.FacePrecincts(j - 1);
    ASSERT_EQ(parents[j].size(), p.count(j));
    for (uint32_t q = 0; q < p.count(j); ++q) {
      for (uint32_t i = p.bounds[j][q]; i < p.bounds[j][q + 1]; ++i) {
        EXPECT_EQ(above[p.face_order[i]], parents[j][q]) << "j " << j << " precinct " << q;
      }
    }
    several += p.count(j - 1) > 1;
  }
  EXPECT_GE(several, 2);  // not only the trivial parent 0
}

TEST(PrecinctPartitionTest, ZeroMeansOnePrecinctPerSubband) {
  const TorusFixture f = MakeTorus();
  const PrecinctPartition p = PartitionIntoPrecincts(*f.h, f.grid, 0);
  ASSERT_EQ(p.levels(), 4);
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(p.count(j), 1u);
    for (uint32_t q : p.FacePrecincts(j)) EXPECT_EQ(q, 0u);
  }
}

}  // namespace
}  // namespace meshwave
