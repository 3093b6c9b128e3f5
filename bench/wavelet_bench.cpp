// Throughput of the lifted-butterfly transform (vertices per second, one
// core) on a semi-regular mesh of more than a million vertices: the shared
// fandisk model (12,946 faces) refined 4 times = 1.66 M vertices.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <iostream>
#include <string>

#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"
#include "meshwave/wavelet.h"

namespace meshwave {
namespace {

const SemiRegularMesh& BigMesh() {
  static const SemiRegularMesh mesh = [] {
    const std::string path =
        std::string(MESHWAVE_SHARED_MESHES) + "/fandisk.obj";
    auto base = ReadMesh(path);
    if (!base.ok()) {
      std::cerr << base.status().ToString() << "\n";
      std::exit(1);
    }
    CleanMesh(*base);
    auto sr = Subdivide(*base, 4, SubdivisionScheme::kButterfly);
    if (!sr.ok()) {
      std::cerr << sr.status().ToString() << "\n";
      std::exit(1);
    }
    return *std::move(sr);
  }();
  return mesh;
}

const TransformSettings kLiftedButterfly{
    Predictor::kButterfly, UpdateWeights::kConstant, FrameMode::kLocal};

void BM_CreateTransform(benchmark::State& state) {
  const SemiRegularMesh& m = BigMesh();
  for (auto _ : state) {
    auto t = WaveletTransform::Create(m.hierarchy, kLiftedButterfly);
    benchmark::DoNotOptimize(t);
  }
  state.SetItemsProcessed(state.iterations() * m.positions.size());
}

void BM_ForwardLiftedButterfly(benchmark::State& state) {
  const SemiRegularMesh& m = BigMesh();
  auto t = WaveletTransform::Create(m.hierarchy, kLiftedButterfly);
  for (auto _ : state) {
    Pyramid p = t->Forward(m.positions);
    benchmark::DoNotOptimize(p.base.data());
  }
  state.SetItemsProcessed(state.iterations() * m.positions.size());
  state.counters["vertices"] = static_cast<double>(m.positions.size());
}

void BM_InverseLiftedButterfly(benchmark::State& state) {
  const SemiRegularMesh& m = BigMesh();
  auto t = WaveletTransform::Create(m.hierarchy, kLiftedButterfly);
  const Pyramid p = t->Forward(m.positions);
  for (auto _ : state) {
    std::vector<Vec3> x = t->Inverse(p);
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(state.iterations() * m.positions.size());
  state.counters["vertices"] = static_cast<double>(m.positions.size());
}

BENCHMARK(BM_CreateTransform)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ForwardLiftedButterfly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InverseLiftedButterfly)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshwave
