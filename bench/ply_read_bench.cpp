// Read speed of the PLY reader on the largest shared mesh (igea.ply, binary
// little-endian, 5 MB): parsing bytes already in memory, and reading from
// disk (page cache warm after the first iteration).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"

namespace meshwave {
namespace {

std::filesystem::path IgeaPath() {
  return std::filesystem::path(MESHWAVE_SHARED_MESHES) / "igea.ply";
}

void BM_ParsePlyInMemory(benchmark::State& state) {
  std::ifstream in(IgeaPath(), std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  if (bytes.empty()) {
    state.SkipWithError(("cannot read " + IgeaPath().string()).c_str());
    return;
  }
  for (auto _ : state) {
    Result<TriMesh> mesh = ParseMesh(bytes, MeshFormat::kPly, "igea.ply");
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(mesh->faces.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(bytes.size()));
}
BENCHMARK(BM_ParsePlyInMemory)->Unit(benchmark::kMillisecond);

void BM_ReadPlyFromDisk(benchmark::State& state) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(IgeaPath(), ec);
  if (ec) {
    state.SkipWithError(("cannot stat " + IgeaPath().string()).c_str());
    return;
  }
  for (auto _ : state) {
    Result<TriMesh> mesh = ReadMesh(IgeaPath());
    if (!mesh.ok()) {
      state.SkipWithError(mesh.status().ToString().c_str());
      return;
    }
    benchmark::DoNotOptimize(mesh->faces.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(size));
}
BENCHMARK(BM_ReadPlyFromDisk)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace meshwave
