// SAWT (Denis et al. 2010a): regions, filters, the encoder's choice, and perfect
// reconstruction with any choice, on synthetic meshes and a shared one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "codec/test_meshes.h"
#include "codec/wavelet/jittered_mesh_testonly.h"
#include "codec/wavelet/reconstruction_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"
#include "semiregular/vertex_rings.h"
#include "test_data.h"
#include "wavelet/prediction_stencils.h"
#include "wavelet/sawt_choice.h"
#include "wavelet/sawt_regions.h"

namespace meshwave {
namespace {

using testing::Icosahedron;
using testing::Jittered;
using testing::MaxError;
using testing::OpenPatch;
using testing::Torus;

// An integer grid of the base positions, as a quantised base would be.
std::vector<IntVec3> Grid(const SemiRegularMesh& mesh, double step) {
  std::vector<IntVec3> grid(mesh.hierarchy->vertex_count(0));
  for (size_t v = 0; v < grid.size(); ++v) {
    for (int a = 0; a < 3; ++a) grid[v][a] = std::llround(mesh.positions[v][a] / step);
  }
  return grid;
}

// The shipped copy of the shared holes_patch_sr2 mesh (data/README.md):
// semi-regular, 2 levels, 7 boundary loops.
SemiRegularMesh HolesPatch() {
  auto read = ReadMesh(meshwave::testing::SampleMesh("holes.off"));
  EXPECT_TRUE(read.ok()) << read.status().ToString();
  auto detected = DetectSemiRegular(*read);
  EXPECT_TRUE(detected.ok()) << detected.status().ToString();
  return detected->mesh;
}

void ExpectRoundTrip(const SemiRegularMesh& mesh, UpdateWeights update, uint32_t alpha,
                     double lambda, const char* what) {
  const double diag = BoundingBox(mesh.positions).Diagonal();
  SawtRegions regions = BuildSawtRegions(*mesh.hierarchy, Grid(mesh, diag / 4096), alpha);
  ASSERT_GT(regions.count, 1u) << what;
  auto plan = ChooseSawtFilters(*mesh.hierarchy, regions, mesh.positions, update, lambda);
  ASSERT_TRUE(plan.ok()) << plan.status().ToString();
  TransformSettings settings{Predictor::kSawt, update, FrameMode::kLocal, *plan};
  auto t = WaveletTransform::Create(mesh.hierarchy, settings);
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  const Pyramid p = t->Forward(mesh.positions);
  EXPECT_LT(MaxError(t->Inverse(p), mesh.positions), 1e-12 * diag) << what;
}

TEST(SawtTest, RoundTripsExactlyWithTheChosenFilters) {
  int n = 0;
  for (const TriMesh& base : {Icosahedron(), OpenPatch(), Torus(3, 5)}) {
    const SemiRegularMesh sr = Jittered(base, 4, 7 + n++);
    for (UpdateWeights update : {UpdateWeights::kNone, UpdateWeights::kConstant}) {
      ExpectRoundTrip(sr, update, 40, 0, "synthetic");
    }
  }
  const SemiRegularMesh holes = HolesPatch();  // 7 boundary loops
  for (UpdateWeights update : {UpdateWeights::kNone, UpdateWeights::kValence}) {
    ExpectRoundTrip(holes, update, 400, 0, "holes.off");
  }
}

// Every filter in every region, boundaries included: perfect
// reconstruction cannot depend on which filters the encoder picks.
TEST(SawtTest, RoundTripsExactlyWithAnyFilters) {
  for (const SemiRegularMesh& mesh : {Jittered(OpenPatch(), 4, 3), HolesPatch()}) {
    const double diag = BoundingBox(mesh.positions).Diagonal();
    auto plan = std::make_shared<SawtPlan>();
    plan->regions = BuildSawtRegions(*mesh.hierarchy, Grid(mesh, diag / 1000), 50);
    std::mt19937 rng(11);
    for (int j = 0; j < mesh.levels(); ++j) {
      plan->filters.emplace_back();
      for (uint32_t r = 0; r < plan->regions.count; ++r) {
        plan->filters[j].push_back(static_cast<SawtFilter>(rng() % kSawtFilterCount));
      }
    }
    for (FrameMode frames : {FrameMode::kLocal, FrameMode::kGlobal}) {
      TransformSettings settings{Predictor::kSawt, UpdateWeights::kConstant, frames, plan};
      auto t = WaveletTransform::Create(mesh.hierarchy, settings);
      ASSERT_TRUE(t.ok()) << t.status().ToString();
      EXPECT_LT(MaxError(t->Inverse(t->Forward(mesh.positions)), mesh.positions), 1e-12 * diag);
    }
  }
}

TEST(SawtTest, FiltersHaveTheSeedWeightsAndReproduceLinearFunctions) {
  const SemiRegularMesh mesh = Jittered(Torus(4, 6), 2, 5);  // no boundary
  const auto& h = *mesh.hierarchy;
  const int j = 1;
  auto rings = VertexRings::Build(h.vertex_count(j), h.faces(j));
  ASSERT_TRUE(rings.ok());
  // Sorted absolute weights of an interior edge of a regular region.
  const std::vector<std::vector<double>> expected = {
      {1.0 / 16, 1.0 / 16, 1.0 / 16, 1.0 / 16, 1.0 / 8, 1.0 / 8, 0.5, 0.5},
      {1.0 / 8, 1.0 / 8, 1.0 / 8, 1.0 / 8, 0.25, 0.25, 0.5, 0.5},
      {0.125, 0.125, 0.375, 0.375},
      {0.5, 0.5},
      {0.5, 0.5},
      {0.25, 0.25, 0.25, 0.25}};
  const Vec3 a(0.3, -1.1, 2.0);
  for (int l = 0; l < kSawtFilterCount; ++l) {
    const std::vector<SawtFilter> all(h.subband_size(j), static_cast<SawtFilter>(l));
    const StencilTable table = BuildSawtStencils(h, j, *rings, all);
    std::vector<double> w;
    double sum = 0;
    for (uint32_t i = table.offsets[0]; i < table.offsets[1]; ++i) {
      w.push_back(std::abs(table.Weight(0, i)));
      sum += table.Weight(0, i);
    }
    std::sort(w.begin(), w.end());
    EXPECT_EQ(w, expected[l]) << "filter f" << l + 1;
    EXPECT_DOUBLE_EQ(sum, 1.0);
    // The weights sum to 1: a constant field is predicted exactly.
    std::vector<Vec3> x(h.vertex_count(j), a);
    for (uint32_t k = 0; k < table.size(); ++k) {
      EXPECT_LT((PredictWithStencil(table, k, x.data()) - a).norm(), 1e-12);
    }
  }
}

// One midpoint refinement of a curved, jittered torus: every odd vertex
// sits at its edge's midpoint, which only f4 (edge) predicts exactly (the
// others read the far vertices c3, c4, which are not coplanar with it), so
// f4 must win in every region; a small lambda only adds index bits.
TEST(SawtTest, ChoiceFindsTheFilterThatFitsTheGeometry) {
  TriMesh base = Torus(8, 12);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Vec3& p : base.positions) p += Vec3(u(rng), u(rng), u(rng));
  auto sr = Subdivide(base, 1, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  const double diag = BoundingBox(sr->positions).Diagonal();
  SawtRegions regions = BuildSawtRegions(*sr->hierarchy, Grid(*sr, diag / 1000), 20);
  ASSERT_GT(regions.count, 4u);
  for (double lambda : {0.0, 1e-6}) {
    auto plan = ChooseSawtFilters(*sr->hierarchy, regions, sr->positions,
                                  UpdateWeights::kNone, lambda);
    ASSERT_TRUE(plan.ok());
    const auto usage = SawtFilterUsage(*sr->hierarchy, **plan);
    EXPECT_GT(usage[static_cast<int>(SawtFilter::kEdge)], regions.count / 2);
    for (int l = 0; l < kSawtFilterCount; ++l) {
      if (l != static_cast<int>(SawtFilter::kEdge)) {
        EXPECT_EQ(usage[l], 0u) << "f" << l + 1;
      }
    }
  }
}

TEST(SawtTest, RegionsPartitionTheBaseAndRespectAlpha) {
  const SemiRegularMesh mesh = HolesPatch();
  const auto& h = *mesh.hierarchy;
  const double diag = BoundingBox(mesh.positions).Diagonal();
  const auto grid = Grid(mesh, diag / 4096);
  for (uint32_t alpha : {100u, 400u, 2000u}) {
    const SawtRegions regions = BuildSawtRegions(h, grid, alpha);
    std::vector<uint32_t> held(regions.count, 0);
    for (int j = 0; j < h.levels(); ++j) {
      for (uint32_t r : SawtOddVertexRegions(h, j, regions.face_region)) {
        ASSERT_LT(r, regions.count);
        ++held[r];
      }
    }
    uint32_t over = 0;
    for (uint32_t n : held) {
      EXPECT_GT(n, 0u);  // leaves are non-empty
      // A leaf holds >= alpha only when it cannot be split (one face).
      over += n >= alpha ? 1 : 0;
    }
    EXPECT_LE(over, regions.count / 10) << "alpha " << alpha;
    const uint32_t odd = h.vertex_count(h.levels()) - h.vertex_count(0);
    EXPECT_GE(regions.count, odd / alpha) << "alpha " << alpha;
  }
}

// The decoder rebuilds the regions from the split flags and its own copy of
// the integer base grid: the same membership for every vertex.
TEST(SawtTest, DecoderReplayGivesTheEncodersRegions) {
  for (const SemiRegularMesh& mesh : {HolesPatch(), Jittered(Icosahedron(), 4, 9)}) {
    const double diag = BoundingBox(mesh.positions).Diagonal();
    const auto grid = Grid(mesh, diag / 4096);
    const SawtRegions encoded = BuildSawtRegions(*mesh.hierarchy, grid, 100);
    size_t next = 0;
    const SawtRegions replayed = ReplaySawtRegions(*mesh.hierarchy, grid, [&](int) {
      return next < encoded.split_flags.size() ? encoded.split_flags[next++] : 0;
    });
    EXPECT_EQ(next, encoded.split_flags.size());
    EXPECT_EQ(replayed.count, encoded.count);
    EXPECT_EQ(replayed.face_region, encoded.face_region);
  }
}

}  // namespace
}  // namespace meshwave
