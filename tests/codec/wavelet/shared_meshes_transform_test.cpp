// Perfect reconstruction on real meshes: every shared mesh small enough to be
// a base mesh (or the base recovered from a semi-regular one) is refined 3 to
// 6 levels, roughened, and sent through every transform and back. Under a
// sanitizer the refinement stops at 250,000 faces (from 1 level on): the
// same code paths, a tenth of the work.
#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"
#include "test_data.h"

namespace meshwave {
namespace {

// igea (268 k faces) would give 8.6 M vertices at 3 levels: left out.
constexpr size_t kMaxBaseFaces = 100000;
constexpr double kMaxFinestFaces =
    testing::kUnderSanitizer ? 2.5e5 : 2.5e6;  // beyond the minimum levels
constexpr int kMinLevels = testing::kUnderSanitizer ? 1 : 3;
// Bases above this many faces run the two extreme transforms only, to keep
// the suite fast on CI (their finest level has 2-3 M vertices).
constexpr size_t kLargeBaseFaces = 20000;

// The base mesh a file provides: its recovered base if semi-regular, else
// itself when small and manifold. Empty with a reason otherwise.
struct Base {
  TriMesh mesh;
  std::string skip_reason;
};

Base BaseOf(const std::filesystem::path& path) {
  auto read = ReadMesh(path);
  if (!read.ok()) return {{}, read.status().ToString()};
  TriMesh mesh = *std::move(read);
  CleanMesh(mesh);
  auto detected = DetectSemiRegular(mesh);
  if (detected.ok()) return {detected->mesh.Level(0), ""};
  if (mesh.faces.size() > kMaxBaseFaces) {
    return {{}, std::to_string(mesh.faces.size()) +
                    " faces: too large to serve as a base mesh"};
  }
  return {mesh, ""};
}

int LevelsFor(const TriMesh& base) {
  int levels = kMinLevels;
  while (levels < 6 &&
         base.faces.size() * std::pow(4.0, levels + 1) <= kMaxFinestFaces) {
    ++levels;
  }
  return levels;
}

void ExpectPerfectReconstruction(const std::filesystem::path& path) {
  const Base base = BaseOf(path);
  if (!base.skip_reason.empty()) {
    std::cout << "[pr] " << path.filename().string() << ": not a base mesh ("
              << base.skip_reason << ")\n";
    return;
  }
  const int levels = LevelsFor(base.mesh);
  auto sr = Subdivide(base.mesh, levels, SubdivisionScheme::kButterfly);
  if (!sr.ok()) {
    // Only a non-manifold base may be refused, and it must say so.
    EXPECT_EQ(sr.status().code(), StatusCode::kNotManifold)
        << sr.status().ToString();
    std::cout << "[pr] " << path.filename().string() << ": refused ("
              << sr.status().message() << ")\n";
    return;
  }
  const double diag = BoundingBox(sr->positions).Diagonal();
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 1e-3 * diag);
  for (Vec3& p : sr->positions) p += Vec3(noise(rng), noise(rng), noise(rng));

  const TransformSettings transforms[] = {
      {Predictor::kLinear, UpdateWeights::kNone, FrameMode::kLocal},
      {Predictor::kLoop, UpdateWeights::kConstant, FrameMode::kLocal},
      {Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kLocal},
      {Predictor::kButterfly, UpdateWeights::kNone, FrameMode::kLocal}};
  const size_t count = base.mesh.faces.size() > kLargeBaseFaces ? 2 : 4;
  for (size_t t_index = 0; t_index < count; ++t_index) {
    const TransformSettings& settings = transforms[count == 2 ? t_index * 2 : t_index];
    auto t = WaveletTransform::Create(sr->hierarchy, settings);
    ASSERT_TRUE(t.ok()) << t.status().ToString();
    const std::vector<Vec3> back = t->Inverse(t->Forward(sr->positions));
    double worst = 0;
    for (size_t v = 0; v < back.size(); ++v) {
      worst = std::max(worst, (back[v] - sr->positions[v]).norm());
    }
    EXPECT_LT(worst, 1e-9 * diag)
        << path << " " << PredictorName(settings.predictor) << "/"
        << UpdateWeightsName(settings.update);
    std::cout << "[pr] " << path.filename().string() << ": "
              << sr->positions.size() << " vertices, " << levels << " levels, "
              << PredictorName(settings.predictor) << "/"
              << UpdateWeightsName(settings.update)
              << " max error = " << worst / diag << " x diagonal\n";
  }
}

TEST(SharedMeshesTransformTest, PerfectReconstructionOnEveryBaseMesh) {
  MESHWAVE_REQUIRE_SHARED_MESH();
  const auto files = testing::AllSharedMeshes();
  ASSERT_GE(files.size(), 10u) << "shared meshes missing in "
                               << testing::SharedMeshDir();
  for (const auto& path : files) ExpectPerfectReconstruction(path);
}

TEST(SharedMeshesTransformTest, PerfectReconstructionOnSampleMeshes) {
  ExpectPerfectReconstruction(testing::SampleMesh("elephant.off"));
  ExpectPerfectReconstruction(testing::SampleMesh("holes.off"));
}

}  // namespace
}  // namespace meshwave
