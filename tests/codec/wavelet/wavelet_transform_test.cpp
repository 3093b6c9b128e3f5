#include <gtest/gtest.h>

#include <random>
#include <thread>
#include <vector>

#include "codec/test_meshes.h"
#include "codec/wavelet/jittered_mesh_testonly.h"
#include "codec/wavelet/reconstruction_testonly.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"
#include "semiregular/vertex_rings.h"
#include "wavelet/local_frames.h"
#include "wavelet/prediction_stencils.h"

namespace meshwave {
namespace {

using testing::Icosahedron;
using testing::Jittered;
using testing::MaxError;
using testing::OpenPatch;
using testing::Torus;

struct Case {
  Predictor predictor;
  UpdateWeights update;
  FrameMode frames;
};

class PerfectReconstruction : public ::testing::TestWithParam<Case> {};

TEST_P(PerfectReconstruction, InverseUndoesForward) {
  const Case c = GetParam();
  for (const TriMesh& base : {Icosahedron(), OpenPatch(), Torus(3, 5)}) {
    const SemiRegularMesh sr = Jittered(base, 4, 42);
    auto t = WaveletTransform::Create(sr.hierarchy,
                                      {c.predictor, c.update, c.frames});
    ASSERT_TRUE(t.ok()) << t.status().ToString();
    const Pyramid p = t->Forward(sr.positions);
    ASSERT_EQ(p.base.size(), sr.hierarchy->vertex_count(0));
    ASSERT_EQ(p.levels(), 4);
    const double diag = BoundingBox(sr.positions).Diagonal();
    EXPECT_LT(MaxError(t->Inverse(p), sr.positions), 1e-12 * diag);
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllTransforms, PerfectReconstruction,
    ::testing::Values(
        Case{Predictor::kLinear, UpdateWeights::kNone, FrameMode::kLocal},
        Case{Predictor::kLinear, UpdateWeights::kConstant, FrameMode::kLocal},
        Case{Predictor::kButterfly, UpdateWeights::kNone, FrameMode::kLocal},
        Case{Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kLocal},
        Case{Predictor::kButterfly, UpdateWeights::kValence, FrameMode::kLocal},
        Case{Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kGlobal},
        Case{Predictor::kLoop, UpdateWeights::kNone, FrameMode::kLocal},
        Case{Predictor::kLoop, UpdateWeights::kConstant, FrameMode::kLocal}),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      const Case& c = param_info.param;
      return std::string(PredictorName(c.predictor)) + "_" +
             UpdateWeightsName(c.update) + "_" +
             (c.frames == FrameMode::kLocal ? "local" : "global");
    });

TEST(WaveletTransformTest, SchemeReproducesItsOwnSubdivisionWithZeroDetail) {
  for (auto [scheme, predictor] :
       {std::pair{SubdivisionScheme::kMidpoint, Predictor::kLinear},
        std::pair{SubdivisionScheme::kButterfly, Predictor::kButterfly}}) {
    for (const TriMesh& base : {Icosahedron(), OpenPatch(), Torus(3, 5)}) {
      auto sr = Subdivide(base, 3, scheme);
      ASSERT_TRUE(sr.ok());
      auto t = WaveletTransform::Create(
          sr->hierarchy, {predictor, UpdateWeights::kNone, FrameMode::kLocal});
      ASSERT_TRUE(t.ok());
      const Pyramid p = t->Forward(sr->positions);
      for (const auto& band : p.subbands) {
        for (const Vec3& d : band) EXPECT_LT(d.norm(), 1e-12);
      }
    }
  }
}

// Every level of an on-first-use transform, asked in any order and from
// several threads, is bit for bit the level of one built all at once.
class OnFirstUse : public ::testing::TestWithParam<Case> {};

TEST_P(OnFirstUse, GivesEveryLevelAsTheTransformBuiltAllAtOnce) {
  const Case c = GetParam();
  const SemiRegularMesh sr = Jittered(Torus(3, 5), 4, 7);
  const TransformSettings settings{c.predictor, c.update, c.frames};
  auto all = WaveletTransform::Create(sr.hierarchy, settings);
  ASSERT_TRUE(all.ok());
  const Pyramid p = all->Forward(sr.positions);
  const int levels = sr.hierarchy->levels();
  std::vector<std::vector<Vec3>> expected;
  for (int level = 0; level <= levels; ++level) expected.push_back(all->Inverse(p, level));
  // In order, finest first, and from the middle out.
  for (const std::vector<int>& order :
       {std::vector<int>{0, 1, 2, 3, 4}, {4, 3, 2, 1, 0}, {2, 4, 0, 3, 1}}) {
    auto lazy = WaveletTransform::Create(sr.hierarchy, settings,
                                         WaveletTransform::Stencils::kOnFirstUse);
    ASSERT_TRUE(lazy.ok());
    EXPECT_EQ(lazy->levels(), levels);
    for (int level : order) EXPECT_EQ(lazy->Inverse(p, level), expected[level]) << level;
  }
  // Forward builds what it needs too, and analyses as the other.
  auto lazy = WaveletTransform::Create(sr.hierarchy, settings,
                                       WaveletTransform::Stencils::kOnFirstUse);
  ASSERT_TRUE(lazy.ok());
  const Pyramid q = lazy->Forward(sr.positions);
  EXPECT_EQ(q.base, p.base);
  EXPECT_EQ(q.subbands, p.subbands);
}

TEST_P(OnFirstUse, InPlaceInverseIsTheInverse) {
  const Case c = GetParam();
  const SemiRegularMesh sr = Jittered(OpenPatch(), 3, 13);
  const TransformSettings settings{c.predictor, c.update, c.frames};
  for (auto when : {WaveletTransform::Stencils::kAllNow, WaveletTransform::Stencils::kOnFirstUse}) {
    auto t = WaveletTransform::Create(sr.hierarchy, settings, when);
    ASSERT_TRUE(t.ok());
    const Pyramid p = t->Forward(sr.positions);
    for (int level = 0; level <= sr.hierarchy->levels(); ++level) {
      // The pyramid laid out level by level, with finer subbands after it
      // that must not be read.
      std::vector<Vec3> x = p.base;
      for (const auto& band : p.subbands) x.insert(x.end(), band.begin(), band.end());
      t->InverseInPlace(x, level);
      EXPECT_EQ(x, t->Inverse(p, level)) << level;
    }
  }
}

TEST_P(OnFirstUse, TwoThreadsAskingAtOnceGetTheSameLevels) {
  const Case c = GetParam();
  const SemiRegularMesh sr = Jittered(Icosahedron(), 4, 11);
  const TransformSettings settings{c.predictor, c.update, c.frames};
  auto all = WaveletTransform::Create(sr.hierarchy, settings);
  ASSERT_TRUE(all.ok());
  const Pyramid p = all->Forward(sr.positions);
  const std::vector<Vec3> finest = all->Inverse(p);
  const std::vector<Vec3> coarse = all->Inverse(p, 2);
  for (int round = 0; round < 8; ++round) {
    auto lazy = WaveletTransform::Create(sr.hierarchy, settings,
                                         WaveletTransform::Stencils::kOnFirstUse);
    ASSERT_TRUE(lazy.ok());
    std::vector<Vec3> a, b, c3;
    // One thread builds ahead level by level while two draw meshes.
    std::thread ahead([&] {
      for (int j = 0; j < lazy->levels(); ++j) lazy->PrepareLevel(j);
    });
    std::thread fine([&] { a = lazy->Inverse(p); });
    std::thread mid([&] { c3 = lazy->Inverse(p, 2); });
    b = lazy->Inverse(p, round % 5);
    ahead.join();
    fine.join();
    mid.join();
    EXPECT_EQ(a, finest);
    EXPECT_EQ(c3, coarse);
    EXPECT_EQ(b, all->Inverse(p, round % 5));
  }
}

INSTANTIATE_TEST_SUITE_P(
    SomeTransforms, OnFirstUse,
    ::testing::Values(
        Case{Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kLocal},
        Case{Predictor::kButterfly, UpdateWeights::kValence, FrameMode::kGlobal},
        Case{Predictor::kLoop, UpdateWeights::kNone, FrameMode::kLocal},
        Case{Predictor::kLinear, UpdateWeights::kConstant, FrameMode::kLocal}),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      const Case& c = param_info.param;
      return std::string(PredictorName(c.predictor)) + "_" +
             UpdateWeightsName(c.update) + "_" +
             (c.frames == FrameMode::kLocal ? "local" : "global");
    });

TEST(WaveletTransformTest, UnliftedCoarseLevelsAreSubsamples) {
  const SemiRegularMesh sr = Jittered(Icosahedron(), 3, 5);
  auto t = WaveletTransform::Create(
      sr.hierarchy,
      {Predictor::kButterfly, UpdateWeights::kNone, FrameMode::kLocal});
  ASSERT_TRUE(t.ok());
  const Pyramid p = t->Forward(sr.positions);
  for (int level = 0; level <= 3; ++level) {
    const std::vector<Vec3> coarse = t->Inverse(p, level);
    ASSERT_EQ(coarse.size(), sr.hierarchy->vertex_count(level));
    EXPECT_LT(MaxError(coarse, std::vector<Vec3>(sr.positions.begin(),
                                                 sr.positions.begin() +
                                                     coarse.size())),
              1e-12);
  }
}

TEST(WaveletTransformTest, LiftedCoarseLevelSmoothsButStaysClose) {
  const SemiRegularMesh sr = Jittered(Icosahedron(), 3, 6);
  auto t = WaveletTransform::Create(
      sr.hierarchy,
      {Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kLocal});
  ASSERT_TRUE(t.ok());
  const Pyramid p = t->Forward(sr.positions);
  const std::vector<Vec3> coarse = t->Inverse(p, 1);
  const std::vector<Vec3> sub(sr.positions.begin(),
                              sr.positions.begin() + coarse.size());
  const double e = MaxError(coarse, sub);
  EXPECT_GT(e, 1e-6);  // the update moved the coarse vertices
  EXPECT_LT(e, 0.2);   // but only by a fraction of the jitter-scale details
}

TEST(StencilTest, EveryStencilSumsToOne) {
  for (Predictor predictor :
       {Predictor::kLinear, Predictor::kButterfly, Predictor::kLoop}) {
    for (const TriMesh& base : {Icosahedron(), OpenPatch(), Torus(3, 5)}) {
      auto h = SemiRegularHierarchy::Build(
          static_cast<uint32_t>(base.positions.size()), base.faces, 2);
      ASSERT_TRUE(h.ok());
      for (int j = 0; j < 2; ++j) {
        auto rings = VertexRings::Build((*h)->vertex_count(j), (*h)->faces(j));
        ASSERT_TRUE(rings.ok());
        const StencilTable s = BuildPredictionStencils(**h, j, *rings, predictor);
        ASSERT_EQ(s.offsets.size(), (*h)->subband_size(j) + 1);
        for (size_t k = 0; k + 1 < s.offsets.size(); ++k) {
          double sum = 0;
          for (uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) {
            EXPECT_LT(s.indices[i], (*h)->vertex_count(j));
            sum += s.Weight(k, i);
          }
          EXPECT_NEAR(sum, 1.0, 1e-12) << PredictorName(predictor) << " k=" << k;
        }
      }
    }
  }
}

TEST(StencilTest, ButterflyUsesEightPointRuleOnRegularInteriorEdges) {
  // On the torus every vertex has valence 6: all stencils have 8 points with
  // weights 1/2, 1/2, 1/8, 1/8 and four times -1/16.
  const TriMesh torus = Torus(6, 7);
  auto h = SemiRegularHierarchy::Build(42, torus.faces, 1);
  ASSERT_TRUE(h.ok());
  auto rings = VertexRings::Build(42, torus.faces);
  ASSERT_TRUE(rings.ok());
  const StencilTable s =
      BuildPredictionStencils(**h, 0, *rings, Predictor::kButterfly);
  for (size_t k = 0; k + 1 < s.offsets.size(); ++k) {
    std::vector<double> w;
    for (uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) {
      w.push_back(s.Weight(k, i));
    }
    std::sort(w.begin(), w.end());
    EXPECT_EQ(w, (std::vector<double>{-1.0 / 16, -1.0 / 16, -1.0 / 16,
                                      -1.0 / 16, 0.125, 0.125, 0.5, 0.5}));
  }
}

TEST(StencilTest, ButterflyUsesFourPointRuleOnBoundaryEdges) {
  const TriMesh patch = OpenPatch();
  auto h = SemiRegularHierarchy::Build(
      static_cast<uint32_t>(patch.positions.size()), patch.faces, 1);
  ASSERT_TRUE(h.ok());
  auto rings = VertexRings::Build(static_cast<uint32_t>(patch.positions.size()),
                                  patch.faces);
  ASSERT_TRUE(rings.ok());
  const StencilTable s =
      BuildPredictionStencils(**h, 0, *rings, Predictor::kButterfly);
  int boundary_edges = 0;
  for (size_t k = 0; k + 1 < s.offsets.size(); ++k) {
    if ((*h)->edge_faces(0)[k][1] != SemiRegularHierarchy::kNone) continue;
    ++boundary_edges;
    std::vector<double> w;
    for (uint32_t i = s.offsets[k]; i < s.offsets[k + 1]; ++i) {
      w.push_back(s.Weight(k, i));
    }
    std::sort(w.begin(), w.end());
    EXPECT_EQ(w, (std::vector<double>{-1.0 / 16, -1.0 / 16, 9.0 / 16, 9.0 / 16}));
  }
  EXPECT_GT(boundary_edges, 5);
}

TEST(LocalFrameTest, FramesAreOrthonormalAndRightHanded) {
  const SemiRegularMesh sr = Jittered(OpenPatch(), 2, 3);
  std::vector<Vec3> normals;
  for (int j = 0; j < 2; ++j) {
    const LevelFrames frames(*sr.hierarchy, j, sr.positions, normals);
    for (uint32_t k = 0; k < sr.hierarchy->subband_size(j); ++k) {
      const Frame f = frames(k);
      EXPECT_NEAR(f.n.norm(), 1, 1e-12);
      EXPECT_NEAR(f.t1.norm(), 1, 1e-12);
      EXPECT_NEAR(f.n.dot(f.t1), 0, 1e-12);
      EXPECT_LT((f.n.cross(f.t1) - f.t2).norm(), 1e-12);
      const Vec3 d(0.3, -1.2, 2.5);
      EXPECT_LT((f.ToGlobal(f.ToLocal(d)) - d).norm(), 1e-12);
    }
  }
}

TEST(LocalFrameTest, DegenerateInputsStillGiveAFrame) {
  const std::vector<std::pair<Vec3, Vec3>> hints = {
      {Vec3::Zero(), Vec3::Zero()},
      {Vec3(0, 0, 2), Vec3::Zero()},
      {Vec3::Zero(), Vec3(1, 1, 0)},
      {Vec3(0, 0, 1), Vec3(0, 0, 3)}};
  for (const auto& [n, t] : hints) {
    const Frame f = MakeFrame(n, t);
    EXPECT_NEAR(f.n.norm(), 1, 1e-12);
    EXPECT_NEAR(f.t1.norm(), 1, 1e-12);
    EXPECT_NEAR(f.n.dot(f.t1), 0, 1e-12);
  }
}

TEST(LocalFrameTest, NormalComponentCarriesNormalDisplacement) {
  // Moving the odd vertices of a flat grid along +z shows up as the normal
  // component only: tangential components stay zero.
  TriMesh grid;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) grid.positions.push_back({1.0 * x, 1.0 * y, 0});
  }
  for (uint32_t y = 0; y < 3; ++y) {
    for (uint32_t x = 0; x < 3; ++x) {
      const uint32_t a = 4 * y + x;
      grid.faces.push_back({a, a + 1, a + 5});
      grid.faces.push_back({a, a + 5, a + 4});
    }
  }
  auto sr = Subdivide(grid, 1, SubdivisionScheme::kMidpoint);
  ASSERT_TRUE(sr.ok());
  for (uint32_t v = 16; v < sr->positions.size(); ++v) sr->positions[v].z() = 0.25;
  auto t = WaveletTransform::Create(
      sr->hierarchy, {Predictor::kLinear, UpdateWeights::kNone, FrameMode::kLocal});
  ASSERT_TRUE(t.ok());
  const Pyramid p = t->Forward(sr->positions);
  for (const Vec3& d : p.subbands[0]) {
    EXPECT_NEAR(d[0], 0.25, 1e-12);
    EXPECT_NEAR(d[1], 0, 1e-12);
    EXPECT_NEAR(d[2], 0, 1e-12);
  }
}

}  // namespace
}  // namespace meshwave
