#include <gtest/gtest.h>

#include <set>

#include "codec/test_meshes.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave {
namespace {

using testing::Icosahedron;
using testing::OpenPatch;
using testing::Torus;

std::shared_ptr<const SemiRegularHierarchy> BuildOrDie(const TriMesh& base,
                                                       int levels) {
  auto h = SemiRegularHierarchy::Build(
      static_cast<uint32_t>(base.positions.size()), base.faces, levels);
  EXPECT_TRUE(h.ok()) << h.status().ToString();
  return *h;
}

class HierarchyShapes : public ::testing::TestWithParam<int> {
 protected:
  TriMesh Base() const {
    switch (GetParam()) {
      case 0: return Icosahedron();
      case 1: return OpenPatch();
      default: return Torus(3, 5);
    }
  }
};

TEST_P(HierarchyShapes, CountsFollowOneToFourSplits) {
  const TriMesh base = Base();
  auto h = BuildOrDie(base, 4);
  ASSERT_EQ(h->levels(), 4);
  for (int j = 0; j < 4; ++j) {
    EXPECT_EQ(h->vertex_count(j + 1), h->vertex_count(j) + h->subband_size(j));
    EXPECT_EQ(h->faces(j + 1).size(), 4 * h->faces(j).size());
    if (j + 1 < 4) {
      EXPECT_EQ(h->subband_size(j + 1),
                2 * h->subband_size(j) + 3 * h->faces(j).size());
    }
  }
}

TEST_P(HierarchyShapes, FaceEdgesMatchFaceCorners) {
  auto h = BuildOrDie(Base(), 3);
  for (int j = 0; j < 3; ++j) {
    const auto& faces = h->faces(j);
    const auto& edges = h->edges(j);
    std::vector<int> uses(edges.size(), 0);
    for (size_t f = 0; f < faces.size(); ++f) {
      for (int i = 0; i < 3; ++i) {
        const Edge& e = edges[h->face_edges(j)[f][i]];
        const std::set<uint32_t> want{faces[f][i], faces[f][(i + 1) % 3]};
        EXPECT_EQ((std::set<uint32_t>{e[0], e[1]}), want);
        ++uses[h->face_edges(j)[f][i]];
      }
    }
    for (int u : uses) EXPECT_TRUE(u == 1 || u == 2);
  }
}

TEST_P(HierarchyShapes, NoEdgeJoinsTwoEvenVertices) {
  auto h = BuildOrDie(Base(), 3);
  for (int j = 1; j < 3; ++j) {
    for (const Edge& e : h->edges(j)) {
      EXPECT_FALSE(e[0] < h->vertex_count(j - 1) &&
                   e[1] < h->vertex_count(j - 1));
    }
  }
}

TEST_P(HierarchyShapes, ChildEdgesRunLikeTheirParent) {
  // With midpoint positions every child edge is parallel to its parent.
  const TriMesh base = Base();
  auto sr = Subdivide(base, 3, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  const auto& h = *sr->hierarchy;
  for (int j = 1; j < 3; ++j) {
    for (uint32_t k = 0; k < h.subband_size(j); ++k) {
      const Edge& c = h.edges(j)[k];
      const Edge& p = h.edges(j - 1)[h.Parent(j, k)];
      const Vec3 dc = sr->positions[c[1]] - sr->positions[c[0]];
      const Vec3 dp = sr->positions[p[1]] - sr->positions[p[0]];
      EXPECT_NEAR(dc.normalized().dot(dp.normalized()), 1.0, 1e-12)
          << "level " << j << " coefficient " << k;
    }
  }
}

TEST_P(HierarchyShapes, ChildrenAndParentsAgreeAndPartition) {
  auto h = BuildOrDie(Base(), 4);
  for (int j = 0; j + 1 < 4; ++j) {
    std::vector<int> seen(h->subband_size(j + 1), 0);
    for (uint32_t k = 0; k < h->subband_size(j); ++k) {
      std::array<uint32_t, 4> children;
      const int n = h->Children(j, k, children);
      const bool boundary =
          h->edge_faces(j)[k][1] == SemiRegularHierarchy::kNone;
      EXPECT_EQ(n, boundary ? 3 : 4);
      for (int i = 0; i < n; ++i) {
        EXPECT_EQ(h->Parent(j + 1, children[i]), k);
        ++seen[children[i]];
      }
    }
    for (int s : seen) EXPECT_EQ(s, 1);
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, HierarchyShapes, ::testing::Values(0, 1, 2));

TEST(HierarchyTest, ParentEdgeOfOddVertexIsTheSplitEdge) {
  auto sr = Subdivide(Icosahedron(), 2, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  const auto& h = *sr->hierarchy;
  for (int j = 0; j < 2; ++j) {
    for (uint32_t k = 0; k < h.subband_size(j); ++k) {
      const Edge& e = h.edges(j)[k];
      const Vec3 mid = 0.5 * (sr->positions[e[0]] + sr->positions[e[1]]);
      EXPECT_LT((sr->positions[h.vertex_count(j) + k] - mid).norm(), 1e-12);
    }
  }
}

TEST(HierarchyTest, RejectsNonManifoldEdge) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  auto h = SemiRegularHierarchy::Build(5, m.faces, 1);
  ASSERT_FALSE(h.ok());
  EXPECT_EQ(h.status().code(), StatusCode::kNotManifold);
  EXPECT_NE(h.status().message().find("edge"), std::string::npos);
}

TEST(HierarchyTest, RejectsInconsistentOrientation) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.faces = {{0, 1, 2}, {1, 2, 3}};  // both run 1 -> 2
  auto h = SemiRegularHierarchy::Build(4, m.faces, 1);
  ASSERT_FALSE(h.ok());
  EXPECT_EQ(h.status().code(), StatusCode::kNotManifold);
}

TEST(HierarchyTest, RejectsNonManifoldVertex) {
  // Two triangles touching at vertex 0 only.
  TriMesh m;
  m.faces = {{0, 1, 2}, {0, 3, 4}};
  auto h = SemiRegularHierarchy::Build(5, m.faces, 1);
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.status().message().find("vertex 0"), std::string::npos);
}

TEST(HierarchyTest, RejectsUnusedVertexAndBadLevels) {
  const TriMesh ico = Icosahedron();
  EXPECT_FALSE(SemiRegularHierarchy::Build(13, ico.faces, 1).ok());
  EXPECT_FALSE(SemiRegularHierarchy::Build(12, ico.faces, -1).ok());
  EXPECT_FALSE(SemiRegularHierarchy::Build(12, ico.faces, 13).ok());
  EXPECT_FALSE(SemiRegularHierarchy::Build(12, {}, 1).ok());
}

TEST(HierarchyTest, RejectsHierarchiesBeyondTheSizeCap) {
  auto h = SemiRegularHierarchy::Build(12, Icosahedron().faces, 12);
  ASSERT_FALSE(h.ok());  // 20 * 4^12 faces > 2^27
  EXPECT_NE(h.status().message().find("2^27"), std::string::npos);
}

}  // namespace
}  // namespace meshwave
