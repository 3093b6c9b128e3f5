#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

#include "meshwave/metrics.h"
#include "test_meshes_testonly.h"

namespace meshwave {
namespace {

SurfaceDistance Measure(const TriMesh& a, const TriMesh& b,
                        const SurfaceDistanceOptions& options = {}) {
  const Result<SurfaceDistance> d = SymmetricSurfaceDistance(a, b, options);
  EXPECT_TRUE(d.ok()) << d.status().ToString();
  return d.ok() ? *d : SurfaceDistance{};
}

// Largest sagitta of the faces of a mesh inscribed in the unit sphere: how
// far the sphere bulges above a face, at the face's circumcentre (inside
// the face for the acute faces of an icosphere).
double MaxSagitta(const TriMesh& mesh) {
  double worst = 0;
  for (const Face& f : mesh.faces) {
    const Vec3& a = mesh.positions[f[0]];
    const Vec3& b = mesh.positions[f[1]];
    const Vec3& c = mesh.positions[f[2]];
    const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
    const double area2 = (b - a).cross(c - a).norm();  // twice the area
    const double circumradius = ab * bc * ca / (2 * area2);
    worst = std::max(worst, 1 - std::sqrt(1 - circumradius * circumradius));
  }
  return worst;
}

TEST(SurfaceDistanceTest, MeshAgainstItselfIsZero) {
  TriMesh sphere = testing::Icosphere(3);
  for (Vec3& p : sphere.positions) p.x() *= 2;  // not a sphere any more
  const SurfaceDistance d = Measure(sphere, sphere);
  const double tolerance = 1e-12 * d.diagonal;
  EXPECT_LT(d.hausdorff, tolerance);
  EXPECT_LT(d.rms, tolerance);
  EXPECT_LT(d.mean, tolerance);
  EXPECT_GT(d.PsnrDb(d.rms), 200);
}

TEST(SurfaceDistanceTest, PatchTranslatedAlongItsNormalIsAtThatDistance) {
  const double h = 0.0123;
  const TriMesh a = testing::GridPatch(10, 0, 0, 1);
  const TriMesh b = testing::Translated(a, Vec3(0, 0, h));
  const SurfaceDistance d = Measure(a, b);
  for (const double value : {d.rms_ab, d.rms_ba, d.rms, d.hausdorff_ab,
                             d.hausdorff_ba, d.hausdorff, d.mean}) {
    EXPECT_NEAR(value, h, 1e-9);
  }
  EXPECT_NEAR(d.diagonal, std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(d.FractionOfDiagonal(d.rms), h / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(d.PsnrDb(d.rms), 20 * std::log10(std::sqrt(2.0) / h), 1e-6);
}

TEST(SurfaceDistanceTest, CoarseSphereVsFineSphereMatchesTheSagitta) {
  const TriMesh coarse = testing::Icosphere(1);  // 80 faces
  const TriMesh fine = testing::Icosphere(4);    // 5120 faces
  const double coarse_sagitta = MaxSagitta(coarse);
  const double fine_sagitta = MaxSagitta(fine);
  ASSERT_LT(fine_sagitta, 0.02 * coarse_sagitta);
  const SurfaceDistance d = Measure(coarse, fine);
  // The fine mesh lies between the unit sphere and fine_sagitta below it;
  // the coarse one reaches coarse_sagitta below the sphere at its face
  // centres. So either one-sided distance is at most coarse_sagitta, and
  // coarse→fine is at least coarse_sagitta - fine_sagitta at a face
  // centre; sampling near (not at) the centre loses a little more.
  EXPECT_LE(d.hausdorff_ab, coarse_sagitta + 1e-12);
  EXPECT_LE(d.hausdorff_ba, coarse_sagitta + 1e-12);
  EXPECT_GE(d.hausdorff_ab, coarse_sagitta - fine_sagitta - 2e-4);
  EXPECT_EQ(d.hausdorff, std::max(d.hausdorff_ab, d.hausdorff_ba));
  // The coarse mesh gets as many face samples as the fine one: 10 per
  // face of the fine mesh, plus its vertices.
  EXPECT_GE(d.samples_a, 10 * fine.faces.size());
}

// A bound on the samples: a mesh over it gets exactly that many face
// samples (no vertex samples), and the RMS stays close to the full one;
// a mesh under it is sampled as without the bound.
TEST(SurfaceDistanceTest, ABoundOnTheSamplesKeepsTheRms) {
  const TriMesh fine = testing::Icosphere(5);    // 20,480 faces
  const TriMesh coarse = testing::Icosphere(2);  // 320 faces
  SurfaceDistanceOptions bounded;
  bounded.max_samples = 5000;
  const SurfaceDistance full = Measure(fine, coarse);
  const SurfaceDistance sparse = Measure(fine, coarse, bounded);
  EXPECT_EQ(sparse.samples_a, 5000u);
  EXPECT_EQ(sparse.samples_b, 5000u);
  EXPECT_GT(full.samples_a, 200000u);
  EXPECT_NEAR(sparse.rms, full.rms, 0.02 * full.rms);
  SurfaceDistanceOptions loose;
  loose.max_samples = 10'000'000;
  const SurfaceDistance same = Measure(fine, coarse, loose);
  EXPECT_EQ(same.samples_a, full.samples_a);
  EXPECT_EQ(same.rms, full.rms);
}

TEST(SurfaceDistanceTest, PatchInsideALargerPatchIsOneSided) {
  const TriMesh small = testing::GridPatch(4, 0.25, 0.25, 0.5);
  const TriMesh large = testing::GridPatch(8, 0, 0, 1);
  const SurfaceDistance d = Measure(small, large);
  EXPECT_LT(d.hausdorff_ab, 1e-15);  // the small patch lies on the large one
  // The large patch's corners are farthest from the small one.
  EXPECT_NEAR(d.hausdorff_ba, 0.25 * std::sqrt(2.0), 1e-12);
  EXPECT_GT(d.rms_ba, 0.05);
  EXPECT_EQ(d.hausdorff, d.hausdorff_ba);
  EXPECT_EQ(d.rms, d.rms_ba);
  EXPECT_NEAR(d.diagonal, 0.5 * std::sqrt(2.0), 1e-15);  // of A, the small one
}

TEST(SurfaceDistanceTest, SameSeedGivesIdenticalResults) {
  const TriMesh a = testing::Icosphere(2);
  const TriMesh b = testing::Icosphere(3);
  SurfaceDistanceOptions options;
  options.seed = 42;
  const SurfaceDistance first = Measure(a, b, options);
  const SurfaceDistance second = Measure(a, b, options);
  EXPECT_EQ(first.rms, second.rms);
  EXPECT_EQ(first.hausdorff, second.hausdorff);
  EXPECT_EQ(first.mean_ba, second.mean_ba);
  options.seed = 43;
  const SurfaceDistance other = Measure(a, b, options);
  EXPECT_NE(first.rms_ab, other.rms_ab);
  EXPECT_NEAR(first.rms_ab, other.rms_ab, 0.01 * first.rms_ab);
}

// Each direction's samples are measured in chunks on the threads and summed
// in chunk order: the same numbers on 1, 2 or 3 threads, across more than
// one batch of samples (over a million).
TEST(SurfaceDistanceTest, ThreadCountDoesNotChangeTheResult) {
  const TriMesh a = testing::Icosphere(2);
  const TriMesh b = testing::Icosphere(3);
  SurfaceDistanceOptions one;
  one.threads = 1;
  one.min_samples = 1100000;
  const SurfaceDistance x = Measure(a, b, one);
  EXPECT_GT(x.samples_a, 1100000u);
  for (int threads : {2, 3}) {
    SCOPED_TRACE(threads);
    SurfaceDistanceOptions other = one;
    other.threads = threads;
    const SurfaceDistance y = Measure(a, b, other);
    EXPECT_EQ(x.rms_ab, y.rms_ab);
    EXPECT_EQ(x.rms_ba, y.rms_ba);
    EXPECT_EQ(x.mean, y.mean);
    EXPECT_EQ(x.hausdorff_ab, y.hausdorff_ab);
    EXPECT_EQ(x.hausdorff_ba, y.hausdorff_ba);
    EXPECT_EQ(x.samples_a, y.samples_a);
    EXPECT_EQ(x.samples_b, y.samples_b);
  }
}

TEST(SurfaceDistanceTest, SampleCountsFollowTheDenserMeshAndTheMinimum) {
  const TriMesh a = testing::GridPatch(2, 0, 0, 1);   // 9 vertices, 8 faces
  const TriMesh b = testing::GridPatch(50, 0, 0, 1);  // 2601 v, 5000 faces
  SurfaceDistanceOptions options;
  options.samples_per_face = 3;
  options.min_samples = 0;
  SurfaceDistance d = Measure(a, b, options);
  EXPECT_EQ(d.samples_a, 9 + 15000u);
  EXPECT_EQ(d.samples_b, 2601 + 15000u);
  options.min_samples = 20000;
  d = Measure(a, b, options);
  EXPECT_EQ(d.samples_a, 9 + 20000u);
}

TEST(SurfaceDistanceTest, UnreferencedVerticesAreNotSampled) {
  const TriMesh a = testing::GridPatch(4, 0, 0, 1);
  TriMesh b = a;
  b.positions.push_back({5, 5, 5});
  const SurfaceDistance d = Measure(a, b);
  EXPECT_LT(d.hausdorff, 1e-15);
  EXPECT_EQ(d.samples_b, d.samples_a);
}

TEST(SurfaceDistanceTest, DegenerateFacesAreMeasuredAsSegments) {
  TriMesh a = testing::GridPatch(4, 0, 0, 1);
  const auto v = static_cast<uint32_t>(a.positions.size());
  a.positions.push_back({0, 0, 1});
  a.positions.push_back({1, 0, 1});
  a.faces.push_back({v, v + 1, v + 1});  // a segment one unit above
  const SurfaceDistance d = Measure(a, testing::GridPatch(4, 0, 0, 1));
  EXPECT_NEAR(d.hausdorff_ab, 1, 1e-12);
  EXPECT_LT(d.hausdorff_ba, 1e-15);
}

TEST(SurfaceDistanceTest, RejectsMeshesWithoutFaces) {
  TriMesh points;
  points.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const TriMesh patch = testing::GridPatch(2, 0, 0, 1);
  const Result<SurfaceDistance> d = SymmetricSurfaceDistance(points, patch);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(d.status().message().find("mesh A"), std::string::npos);
  EXPECT_FALSE(SymmetricSurfaceDistance(patch, points).ok());
}

TEST(SurfaceDistanceTest, RejectsOutOfRangeIndicesAndNonFiniteCoordinates) {
  const TriMesh patch = testing::GridPatch(2, 0, 0, 1);
  TriMesh bad_index = patch;
  bad_index.faces[3][1] = 9;
  const Result<SurfaceDistance> d = SymmetricSurfaceDistance(patch, bad_index);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("face 3"), std::string::npos);
  TriMesh bad_value = patch;
  bad_value.positions[1].z() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(SymmetricSurfaceDistance(bad_value, patch).ok());
}

TEST(SurfaceDistanceTest, RejectsBadSampleCounts) {
  const TriMesh patch = testing::GridPatch(2, 0, 0, 1);
  SurfaceDistanceOptions options;
  options.samples_per_face = -1;
  EXPECT_FALSE(SymmetricSurfaceDistance(patch, patch, options).ok());
  options.samples_per_face = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(SymmetricSurfaceDistance(patch, patch, options).ok());
  options.samples_per_face = 1e12;
  EXPECT_FALSE(SymmetricSurfaceDistance(patch, patch, options).ok());
}

}  // namespace
}  // namespace meshwave
