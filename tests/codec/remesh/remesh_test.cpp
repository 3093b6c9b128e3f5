// Remesh (meshwave/remesh.h) end to end on small meshes built in code:
// closed, open with a hole, genus 1, several components, broken input.
#include "meshwave/remesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "codec/remesh/remesh_meshes_testonly.h"
#include "codec/test_meshes.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/metrics.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "remesh/components.h"
#include "remesh/input_surface.h"
#include "remesh/manifold_repair.h"
#include "remesh/remesh_quality.h"
#include "test_data.h"

namespace meshwave {
namespace {

using testing::Combined;
using testing::ThinCurvedSlab;
using testing::Torus;
using testing::Translated;
using testing::UvSphere;
using testing::WavySheet;

// The acceptance bar of the remesher (docs/REMESH_RESULTS.md): RMS within
// 0.1 % and Hausdorff within 1 % of the diagonal, nothing flipped or
// degenerate, and a mesh that detection recovers with all its levels.
void ExpectFaithful(const TriMesh& input, const RemeshResult& r) {
  const TriMesh finest = r.mesh.Finest();
  EXPECT_EQ(r.finest_vertices, finest.positions.size());
  EXPECT_EQ(r.flipped_faces, 0u);
  EXPECT_EQ(r.degenerate_faces, 0u);
  auto d = SymmetricSurfaceDistance(input, finest);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_LT(d->FractionOfDiagonal(d->rms), 0.001);
  EXPECT_LT(d->FractionOfDiagonal(d->hausdorff), 0.01);
  TriMesh cleaned = finest;
  const CleanReport clean = CleanMesh(cleaned);
  EXPECT_EQ(clean.merged_vertices, 0u);  // no two vertices in one place
  auto detected = DetectSemiRegular(cleaned);
  ASSERT_TRUE(detected.ok()) << detected.status().ToString();
  EXPECT_GE(detected->mesh.levels(), r.levels);
}

Result<RemeshResult> RemeshOrFail(const TriMesh& input,
                                  const RemeshOptions& options = {}) {
  auto r = Remesh(input, options);
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  return r;
}

TEST(RemeshTest, RemeshesAnIrregularSphereCloselyWithTheInputSize) {
  const TriMesh sphere = UvSphere(40, 64);
  auto r = RemeshOrFail(sphere);
  ASSERT_TRUE(r.ok());
  ExpectFaithful(sphere, *r);
  EXPECT_EQ(r->levels, 2);  // 2,500 vertices: too few for 3 levels
  const double ratio = static_cast<double>(r->finest_vertices) /
                       static_cast<double>(sphere.positions.size());
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 1.5);
  EXPECT_EQ(r->components, 1u);
  EXPECT_TRUE(r->warnings.empty()) << r->warnings.front();
}

TEST(RemeshTest, FollowsTheBoundaryAndTheHoleOfAnOpenSheet) {
  const TriMesh sheet = WavySheet(48, 12);
  auto r = RemeshOrFail(sheet);
  ASSERT_TRUE(r.ok());
  ExpectFaithful(sheet, *r);
  const MeshStats stats = ComputeStats(r->mesh.Finest());
  EXPECT_EQ(stats.boundary_loops, 2u);
  EXPECT_GT(r->boundary_vertices, 0u);
  // Boundary vertices lie on the input boundary: the outer square's
  // corners and sides are kept exactly.
  for (const Vec3& p : r->mesh.Finest().positions) {
    EXPECT_LE(std::abs(p.x()), 1 + 1e-12);
    EXPECT_LE(std::abs(p.y()), 1 + 1e-12);
  }
}

TEST(RemeshTest, KeepsTheHandleOfATorus) {
  const TriMesh torus = Torus(64, 24);
  auto r = RemeshOrFail(torus);
  ASSERT_TRUE(r.ok());
  ExpectFaithful(torus, *r);
  const MeshStats stats = ComputeStats(r->mesh.Finest());
  EXPECT_TRUE(stats.closed);
  EXPECT_EQ(stats.genus, 1);
}

TEST(RemeshTest, RemeshesEachComponentOnItsOwn) {
  const TriMesh two =
      Combined(UvSphere(32, 48), Translated(Torus(48, 16), Vec3(4, 0, 0)));
  auto r = RemeshOrFail(two);
  ASSERT_TRUE(r.ok());
  ExpectFaithful(two, *r);
  EXPECT_EQ(r->components, 2u);
  const MeshStats stats = ComputeStats(r->mesh.Finest());
  EXPECT_EQ(stats.components, 2u);
  EXPECT_EQ(stats.genus, 1);  // 0 + 1
}

TEST(RemeshTest, RepairsANonManifoldInput) {
  // Two spheres sharing a vertex (a pinch), a face that duplicates another
  // one the other way round, and a fin: a triangle hanging off an edge, so
  // that edge has three faces.
  TriMesh a = UvSphere(24, 32);
  const TriMesh b = UvSphere(24, 32, 1.0, Vec3(0, 0, -2));
  const auto south = static_cast<uint32_t>(a.positions.size() - 1);
  TriMesh mesh = a;
  const auto offset = static_cast<uint32_t>(a.positions.size());
  mesh.positions.insert(mesh.positions.end(), b.positions.begin() + 1,
                        b.positions.end());
  for (Face f : b.faces) {
    for (uint32_t& v : f) v = v == 0 ? south : v + offset - 1;
    mesh.faces.push_back(f);
  }
  const Face first = mesh.faces[0];
  mesh.faces.push_back({first[0], first[2], first[1]});
  mesh.positions.push_back(Vec3(0, 0, 1.3));
  mesh.faces.push_back(
      {first[0], first[1], static_cast<uint32_t>(mesh.positions.size() - 1)});
  ASSERT_FALSE(ComputeStats(mesh).manifold);

  auto r = RemeshOrFail(mesh);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->cleaning.duplicate_faces, 1u);
  EXPECT_GE(r->non_manifold_vertices, 1u);
  EXPECT_EQ(r->non_manifold_edges, 1u);
  // The fin is a component of its own: tiny, kept, and said so.
  EXPECT_EQ(r->components, 3u);
  EXPECT_EQ(r->tiny_components, 1u);
  bool warned = false;
  for (const std::string& w : r->warnings) {
    warned = warned || w.find("1 tiny component") != std::string::npos;
  }
  EXPECT_TRUE(warned);
  const TriMesh finest = r->mesh.Finest();
  EXPECT_TRUE(ComputeStats(finest).manifold);
  EXPECT_EQ(r->flipped_faces, 0u);
  EXPECT_EQ(r->degenerate_faces, 0u);
  TriMesh cleaned = finest;
  EXPECT_EQ(CleanMesh(cleaned).merged_vertices, 0u);
  EXPECT_TRUE(DetectSemiRegular(cleaned).ok());
}

TEST(RemeshTest, DropsTinyComponentsWhenAskedAndSaysHowMany) {
  TriMesh mesh = UvSphere(24, 32);
  for (int i = 0; i < 3; ++i) {
    const auto v = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(Vec3(3 + i, 0, 0));
    mesh.positions.push_back(Vec3(3.1 + i, 0, 0));
    mesh.positions.push_back(Vec3(3 + i, 0.1, 0));
    mesh.faces.push_back({v, v + 1, v + 2});
  }
  RemeshOptions options;
  options.drop_tiny_components = true;
  auto r = RemeshOrFail(mesh, options);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->dropped_components, 3u);
  EXPECT_EQ(r->dropped_faces, 3u);
  EXPECT_EQ(r->components, 1u);
  ASSERT_FALSE(r->warnings.empty());
  EXPECT_NE(r->warnings.front().find("dropped 3 tiny components"),
            std::string::npos)
      << r->warnings.front();
}

TEST(RemeshTest, DropsComponentsWithoutArea) {
  TriMesh mesh = UvSphere(24, 32);
  const auto v = static_cast<uint32_t>(mesh.positions.size());
  mesh.positions.push_back(Vec3(3, 0, 0));
  mesh.positions.push_back(Vec3(4, 0, 0));
  mesh.positions.push_back(Vec3(5, 0, 0));  // collinear
  mesh.faces.push_back({v, v + 1, v + 2});
  auto r = RemeshOrFail(mesh);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->dropped_components, 1u);
  EXPECT_EQ(r->components, 1u);
}

TEST(RemeshTest, RefusesAMeshWithNothingUsable) {
  TriMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  flat.faces = {{0, 1, 2}, {1, 2, 3}};
  auto r = Remesh(flat);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("no area"), std::string::npos)
      << r.status().message();

  TriMesh repeated;
  repeated.positions = {{0, 0, 0}, {1, 0, 0}};
  repeated.faces = {{0, 1, 1}};
  r = Remesh(repeated);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("nothing usable"), std::string::npos);
}

TEST(RemeshTest, RefusesBrokenInputNamingTheCulprit) {
  TriMesh mesh = UvSphere(6, 8);
  mesh.positions[5].y() = std::nan("");
  auto r = Remesh(mesh);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("vertex 5"), std::string::npos);

  mesh = UvSphere(6, 8);
  mesh.faces[3][1] = 1000;
  r = Remesh(mesh);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("face 3"), std::string::npos);

  EXPECT_FALSE(Remesh(TriMesh{}).ok());
  RemeshOptions bad;
  bad.levels = 9;
  EXPECT_EQ(Remesh(UvSphere(6, 8), bad).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(RemeshTest, HonoursTheRequestedLevelsAndBaseSize) {
  const TriMesh sphere = UvSphere(30, 40);
  RemeshOptions options;
  options.levels = 3;
  options.base_faces = 60;
  auto r = RemeshOrFail(sphere, options);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->levels, 3);
  EXPECT_EQ(r->mesh.levels(), 3);
  EXPECT_EQ(r->target_base_faces, 60u);
  EXPECT_NEAR(static_cast<double>(r->base_faces), 60, 2);
  EXPECT_EQ(r->finest_faces, r->base_faces * 64);
}

TEST(RemeshTest, ReportsProgressFromStartToEnd) {
  RemeshOptions options;
  double last = -1;
  bool ordered = true;
  std::string stages;
  options.progress = [&](std::string_view stage, double fraction) {
    ordered = ordered && fraction >= last && fraction <= 1;
    last = fraction;
    if (stages.find(stage) == std::string::npos) {
      stages.append(stage).append(" ");
    }
  };
  ASSERT_TRUE(Remesh(UvSphere(20, 24), options).ok());
  EXPECT_TRUE(ordered);
  EXPECT_EQ(last, 1.0);
  // "refine" appears when a second attempt keeps missed features.
  EXPECT_TRUE(stages == "repair simplify fit check done " ||
              stages == "repair simplify fit refine check done ")
      << stages;
}

TEST(RemeshTest, GivesTheSameResultForAnyThreadCount) {
  // Big enough (10k vertices) for the fitting to split its loops.
  const TriMesh torus = Torus(160, 64);
  RemeshOptions one, two;
  one.threads = 1;
  two.threads = 2;
  auto a = RemeshOrFail(torus, one);
  auto b = RemeshOrFail(torus, two);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->mesh.positions, b->mesh.positions);
}

// IsFlipped inside a part thinner than a face's sag: a face whose corners
// all lie on the top sheet of a bent slab 0.013 thick, its centroid and
// halfway points 0.012 deep, nearer the bottom sheet. The nearest input
// face there faces the other way (the old test counted the face as
// flipped); the sheet the corners lie on agrees with it. Turned over, the
// same face is still flipped.
TEST(RemeshQualityTest, JudgesAFaceInsideAThinPartByTheSheetOfItsCorners) {
  constexpr double kRadius = 0.3, kThickness = 0.013, kAngle = 0.3;
  TriMesh slab = ThinCurvedSlab(48, kRadius, kThickness, 0.6, 0.3);
  remesh::RepairManifold(slab);
  remesh::Components components = remesh::LabelComponents(slab);
  ASSERT_EQ(components.count, 1u);
  const remesh::InputSurface input(slab, components);
  const auto top = [&](double angle, double y) {
    return Vec3(kRadius * std::sin(angle), y,
                kRadius * std::cos(angle) - kRadius);
  };
  const Vec3 a = top(-kAngle, -0.15), b = top(kAngle, 0),
             c = top(-kAngle, 0.15);
  Vec3 n = (b - a).cross(c - a);
  ASSERT_GT(n.z(), 0);  // facing out of the slab, as the top sheet does
  // The premise: seen from its centroid, the nearest input is the bottom
  // sheet, facing away from the face.
  const remesh::InputSurface::Projection nearest = input.Closest(
      (a + b + c) / 3, Vec3::Zero(), 0, remesh::InputSurface::kNoFace);
  ASSERT_TRUE(nearest.found());
  ASSERT_LT(n.dot(input.FaceNormal(nearest.face)), 0);
  EXPECT_FALSE(
      remesh::IsFlipped(input, a, b, c, 0, remesh::InputSurface::kNoFace));
  EXPECT_TRUE(
      remesh::IsFlipped(input, a, c, b, 0, remesh::InputSurface::kNoFace));
  // A face lying flat on the top sheet, turned over: flipped.
  const Vec3 d = top(0, 0), e = top(0.05, 0), f = top(0, 0.05);
  ASSERT_GT((e - d).cross(f - d).z(), 0);
  EXPECT_FALSE(
      remesh::IsFlipped(input, d, e, f, 0, remesh::InputSurface::kNoFace));
  EXPECT_TRUE(
      remesh::IsFlipped(input, d, f, e, 0, remesh::InputSurface::kNoFace));
}

// A bent plate 0.005 thick (0.4 % of its diagonal), thinner than the
// finest edges of its remesh: faces wrap around its rim and the sag of
// faces on one sheet reaches the other. Before FixFolds and the sheet-aware
// IsFlipped it kept 29 flipped faces; now at most a couple (1 when this
// was written) where a rim corner is cut by the base. Its Hausdorff
// distance (1.6 %) stays above the bar: the 1,000-face base cuts the
// plate's corners, a limit of the base, not of the fitting.
TEST(RemeshTest, LeavesFewFlippedFacesOnAThinBentPlate) {
  const TriMesh slab = ThinCurvedSlab(60, 0.3, 0.005, 0.6, 0.3);
  auto r = RemeshOrFail(slab);
  ASSERT_TRUE(r.ok());
  EXPECT_LE(r->flipped_faces, 2u);
  EXPECT_EQ(r->degenerate_faces, 0u);
  auto d = SymmetricSurfaceDistance(slab, r->mesh.Finest());
  ASSERT_TRUE(d.ok());
  EXPECT_LT(d->FractionOfDiagonal(d->rms), 0.001);
}

// Shared meshes that kept a folded face before FixFolds and SlideOnLoop:
// the bunny's (over a jagged hole boundary, all three corners on it) and
// the cartoon elephant's. About a second in Release.
TEST(RemeshTest, LeavesNoFlippedFaceOnSharedMeshesThatHadOne) {
  MESHWAVE_REQUIRE_SHARED_MESH("bunny_stanford_zipper.ply", "elephant_cartoon_sr2.obj");
  for (const char* name :
       {"bunny_stanford_zipper.ply", "elephant_cartoon_sr2.obj"}) {
    SCOPED_TRACE(name);
    auto mesh = ReadMesh(testing::SharedMesh(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
    auto r = RemeshOrFail(*mesh);
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->flipped_faces, 0u);
    EXPECT_EQ(r->degenerate_faces, 0u);
  }
}

}  // namespace
}  // namespace meshwave
