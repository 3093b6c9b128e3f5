#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "codec/test_meshes.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave {
namespace {

using testing::Icosahedron;
using testing::OpenPatch;
using testing::Shuffled;
using testing::Torus;

std::set<std::array<uint32_t, 3>> RotatedFaces(const std::vector<Face>& faces) {
  std::set<std::array<uint32_t, 3>> out;
  for (Face f : faces) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    out.insert(f);
  }
  return out;
}

// Detecting a shuffled semi-regular mesh gives back J levels, a base with
// the original base's size, and a canonical mesh that maps onto the input.
void ExpectDetectedBack(const TriMesh& base, int levels,
                        SubdivisionScheme scheme, uint32_t seed) {
  auto sr = Subdivide(base, levels, scheme);
  ASSERT_TRUE(sr.ok()) << sr.status().ToString();
  const TriMesh flat = Shuffled(sr->Finest(), seed);
  auto detected = DetectSemiRegular(flat);
  ASSERT_TRUE(detected.ok()) << detected.status().ToString();
  const SemiRegularMesh& m = detected->mesh;
  EXPECT_EQ(m.levels(), levels);
  EXPECT_EQ(m.hierarchy->vertex_count(0), base.positions.size());
  EXPECT_EQ(m.hierarchy->faces(0).size(), base.faces.size());
  ASSERT_EQ(m.positions.size(), flat.positions.size());
  // Same faces once mapped back to input indices, orientation kept.
  std::vector<Face> mapped = m.hierarchy->faces(levels);
  for (Face& f : mapped) {
    for (uint32_t& v : f) v = detected->original_index[v];
  }
  EXPECT_EQ(RotatedFaces(mapped), RotatedFaces(flat.faces));
  for (size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_EQ(m.positions[v], flat.positions[detected->original_index[v]]);
  }
  // The base positions are the original base positions (any order).
  std::vector<std::array<double, 3>> want, got;
  for (const Vec3& p : base.positions) want.push_back({p.x(), p.y(), p.z()});
  for (uint32_t v = 0; v < m.hierarchy->vertex_count(0); ++v) {
    got.push_back({m.positions[v].x(), m.positions[v].y(), m.positions[v].z()});
  }
  if (scheme != SubdivisionScheme::kLoop) {  // Loop moves base vertices
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(want, got);
  }
}

TEST(DetectTest, FindsLevelsOfShuffledClosedMesh) {
  for (int levels = 1; levels <= 4; ++levels) {
    ExpectDetectedBack(Icosahedron(), levels, SubdivisionScheme::kButterfly,
                       100 + levels);
  }
}

TEST(DetectTest, FindsLevelsOfMeshWithBoundary) {
  ExpectDetectedBack(OpenPatch(), 3, SubdivisionScheme::kMidpoint, 7);
  ExpectDetectedBack(OpenPatch(), 2, SubdivisionScheme::kLoop, 8);
}

TEST(DetectTest, FindsLevelsOfGenusOneMeshWithoutExtraordinaryVertices) {
  ExpectDetectedBack(Torus(3, 5), 3, SubdivisionScheme::kLoop, 9);
}

TEST(DetectTest, FindsLevelsOfSeveralComponents) {
  // (A torus without extraordinary vertices would do too, but its base is
  // ambiguous: any of the shifted sub-lattices is a valid coarser mesh.)
  TriMesh two = Icosahedron();
  const TriMesh other = OpenPatch();
  const uint32_t offset = static_cast<uint32_t>(two.positions.size());
  for (const Vec3& p : other.positions) two.positions.push_back(p + Vec3(9, 0, 0));
  for (Face f : other.faces) {
    for (uint32_t& v : f) v += offset;
    two.faces.push_back(f);
  }
  ExpectDetectedBack(two, 2, SubdivisionScheme::kButterfly, 10);
}

TEST(DetectTest, RespectsLevelCap) {
  auto sr = Subdivide(Icosahedron(), 3, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  DetectOptions options;
  options.max_levels = 2;
  auto detected = DetectSemiRegular(sr->Finest(), options);
  ASSERT_TRUE(detected.ok());
  EXPECT_EQ(detected->mesh.levels(), 2);
  EXPECT_EQ(detected->mesh.hierarchy->faces(0).size(), 20u * 4);
}

TEST(DetectTest, RefusesIrregularMesh) {
  auto detected = DetectSemiRegular(Icosahedron());
  ASSERT_FALSE(detected.ok());
  EXPECT_EQ(detected.status().code(), StatusCode::kNotSemiRegular);
  EXPECT_NE(detected.status().message().find("no level"), std::string::npos);
}

TEST(DetectTest, RefusesSubdividedMeshWithOneEdgeFlipped) {
  auto sr = Subdivide(Icosahedron(), 1, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  TriMesh m = sr->Finest();
  // Flip the edge shared by faces 0 and 1 of the finest level.
  const Face a = m.faces[0];
  for (size_t g = 1; g < m.faces.size(); ++g) {
    const Face b = m.faces[g];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) {
        if (a[i] == b[(k + 1) % 3] && a[(i + 1) % 3] == b[k]) {
          const uint32_t p = a[(i + 2) % 3], q = b[(k + 2) % 3];
          m.faces[0] = {p, a[i], q};
          m.faces[g] = {q, a[(i + 1) % 3], p};
          auto detected = DetectSemiRegular(m);
          EXPECT_FALSE(detected.ok());
          EXPECT_EQ(detected.status().code(), StatusCode::kNotSemiRegular);
          return;
        }
      }
    }
  }
  FAIL() << "no neighbour of face 0 found";
}

TEST(DetectTest, RefusesNonManifoldInputWithReason) {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  auto detected = DetectSemiRegular(m);
  ASSERT_FALSE(detected.ok());
  EXPECT_NE(detected.status().message().find("manifold"), std::string::npos);
}

}  // namespace
}  // namespace meshwave
