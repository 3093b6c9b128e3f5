// Encoder and decoder throughput (vertices per second, one core) of the 3xC
// stream on a semi-regular mesh of 1.66 M vertices: the shared fandisk
// (12,946 faces) refined 4 times with the butterfly scheme.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <iostream>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/encoder.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_clean.h"
#include "meshwave/mesh_io.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave {
namespace {

const SemiRegularMesh& BigMesh() {
  static const SemiRegularMesh mesh = [] {
    auto base = ReadMesh(std::string(MESHWAVE_SHARED_MESHES) + "/fandisk.obj");
    if (!base.ok()) {
      std::cerr << base.status().ToString() << "\n";
      std::exit(1);
    }
    CleanMesh(*base);
    auto sr = Subdivide(*base, 4, SubdivisionScheme::kButterfly);
    if (!sr.ok()) std::exit(1);
    // Some detail to code: a smooth bump field on top of the butterfly surface.
    for (Vec3& p : sr->positions) p += 0.002 * Vec3(std::sin(40 * p.y()), std::sin(40 * p.z()), std::sin(40 * p.x()));
    return *std::move(sr);
  }();
  return mesh;
}

const EncodedStream& Stream() {
  static const EncodedStream s = [] {
    auto r = EncodeMesh(BigMesh(), EncodeOptions{});
    if (!r.ok()) std::exit(1);
    return *std::move(r);
  }();
  return s;
}

void BM_Encode3xC(benchmark::State& state) {
  const SemiRegularMesh& m = BigMesh();
  EncodeOptions options;
  options.threads = 1;  // one core, as the figures in docs/BENCHMARKS.md
  for (auto _ : state) {
    auto s = EncodeMesh(m, options);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * m.positions.size());
}

void BM_DecodeAllPackets3xC(benchmark::State& state) {
  const EncodedStream& s = Stream();
  uint64_t bytes = 0;
  for (const auto& p : s.packets) bytes += p.size();
  for (auto _ : state) {
    auto d = ProgressiveDecoder::Create(s.header);
    for (uint32_t id = 0; id < s.packets.size(); ++id) {
      if (!(*d)->AddPacket(id, s.packets[id]).ok()) std::exit(1);
    }
    auto positions = (*d)->Positions();
    benchmark::DoNotOptimize(positions.data());
  }
  state.SetItemsProcessed(state.iterations() * s.header.vertices);
  state.counters["stream_bytes"] = static_cast<double>(bytes);
}

// What a client pays before the first packet: parsing the header, the
// hierarchy, the stencils and the octrees, and the base-only mesh.
void BM_DecoderSetup(benchmark::State& state) {
  const EncodedStream& s = Stream();
  for (auto _ : state) {
    auto d = ProgressiveDecoder::Create(s.header);
    auto positions = (*d)->Positions();
    benchmark::DoNotOptimize(positions.data());
  }
  state.SetItemsProcessed(state.iterations() * s.header.vertices);
}

// One refinement step (issue 4: under 50 ms on a 250 k-vertex mesh): one
// more packet in quality order, then the whole mesh reconstructed, on a
// 414 k-vertex mesh (fandisk refined 3 times) whose decoder already holds
// the first half of the packets. Each iteration is one step; the steps
// cycle through the second half of the order.
void BM_RefinementStep(benchmark::State& state) {
  static const EncodedStream s = [] {
    auto base = ReadMesh(std::string(MESHWAVE_SHARED_MESHES) + "/fandisk.obj");
    if (!base.ok()) std::exit(1);
    CleanMesh(*base);
    auto sr = Subdivide(*base, 3, SubdivisionScheme::kButterfly);
    if (!sr.ok()) std::exit(1);
    for (Vec3& p : sr->positions) p += 0.002 * Vec3(std::sin(40 * p.y()), std::sin(40 * p.z()), std::sin(40 * p.x()));
    auto r = EncodeMesh(*sr, EncodeOptions{});
    if (!r.ok()) std::exit(1);
    return *std::move(r);
  }();
  const std::vector<uint32_t> order = PacketOrder(s.header, Progression::kQuality);
  const size_t half = order.size() / 2;
  std::unique_ptr<ProgressiveDecoder> d;
  size_t next = order.size();
  for (auto _ : state) {
    if (next == order.size()) {  // start again from half of the stream
      state.PauseTiming();
      d = std::move(ProgressiveDecoder::Create(s.header)).value();
      for (size_t i = 0; i < half; ++i) {
        if (!d->AddPacket(order[i], s.packets[order[i]]).ok()) std::exit(1);
      }
      next = half;
      state.ResumeTiming();
    }
    const uint32_t id = order[next++];
    if (!d->AddPacket(id, s.packets[id]).ok()) std::exit(1);
    auto positions = d->Positions();
    benchmark::DoNotOptimize(positions.data());
  }
  state.counters["vertices"] = static_cast<double>(s.header.vertices);
}

// A region step (issue 21) on the 1.66 M-vertex stream (default precincts):
// one part of the finest subband's last split packet decoded, against the
// whole packet, each into a decoder holding every other packet; no
// reconstruction (Positions() rebuilds the whole mesh, BM_RefinementStep).
// A part decodes its precinct alone: its cost follows the precinct, not
// the mesh.
struct FinestSplit {
  uint32_t id = 0;
  uint32_t parts = 0;
};

FinestSplit LastSplitPacket(const EncodedStream& s) {
  auto d = ProgressiveDecoder::Create(s.header);
  FinestSplit out;
  for (uint32_t id = 0; id < s.packets.size(); ++id) {
    if ((*d)->PartCount(id) > 0) out = {id, (*d)->PartCount(id)};
  }
  if (out.parts == 0) std::exit(1);
  return out;
}

std::unique_ptr<ProgressiveDecoder> AllBut(const EncodedStream& s, uint32_t missing) {
  auto d = std::move(ProgressiveDecoder::Create(s.header)).value();
  for (uint32_t id = 0; id < s.packets.size(); ++id) {
    if (id != missing && !d->AddPacket(id, s.packets[id]).ok()) std::exit(1);
  }
  return d;
}

void BM_PartOfFinestPacket(benchmark::State& state) {
  const EncodedStream& s = Stream();
  const FinestSplit split = LastSplitPacket(s);
  std::vector<std::string> parts;
  {
    // The parts' payloads, cut as FORMAT.md 2.2 says: P - 1 varint lengths.
    std::string_view in = s.packets[split.id];
    std::vector<uint64_t> lengths;
    for (uint32_t p = 0; p + 1 < split.parts; ++p) {
      uint64_t v = 0;
      for (int shift = 0;; shift += 7) {
        const auto byte = static_cast<uint8_t>(in.front());
        in.remove_prefix(1);
        v |= uint64_t{byte & 0x7fu} << shift;
        if (!(byte & 0x80)) break;
      }
      lengths.push_back(v);
    }
    for (uint64_t n : lengths) {
      parts.emplace_back(in.substr(0, n));
      in.remove_prefix(n);
    }
    parts.emplace_back(in);
  }
  std::unique_ptr<ProgressiveDecoder> d;
  uint32_t next = split.parts;
  uint64_t bytes = 0;
  for (auto _ : state) {
    if (next == split.parts) {
      state.PauseTiming();
      d = AllBut(s, split.id);
      next = 0;
      state.ResumeTiming();
    }
    bytes += parts[next].size();
    if (!d->AddPacketPart(split.id, next, parts[next]).ok()) std::exit(1);
    ++next;
  }
  state.counters["parts"] = split.parts;
  state.counters["part_bytes"] = static_cast<double>(bytes) / static_cast<double>(state.iterations());
}

void BM_WholeFinestPacket(benchmark::State& state) {
  const EncodedStream& s = Stream();
  const FinestSplit split = LastSplitPacket(s);
  for (auto _ : state) {
    state.PauseTiming();
    auto d = AllBut(s, split.id);
    state.ResumeTiming();
    if (!d->AddPacket(split.id, s.packets[split.id]).ok()) std::exit(1);
    state.PauseTiming();
    d.reset();
    state.ResumeTiming();
  }
  state.counters["parts"] = split.parts;
  state.counters["packet_bytes"] = static_cast<double>(s.packets[split.id].size());
}

BENCHMARK(BM_DecoderSetup)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_PartOfFinestPacket)->Unit(benchmark::kMicrosecond)->Iterations(200);
BENCHMARK(BM_WholeFinestPacket)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RefinementStep)->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK(BM_Encode3xC)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(BM_DecodeAllPackets3xC)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace meshwave
