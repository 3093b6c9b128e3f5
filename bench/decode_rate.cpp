// decode_rate: the packet decoder's CPU cost per payload byte, in memory, on
// one core: what "decode keeps up with a 100 Mbit/s stream" is measured by
// (docs/BENCHMARKS.md, "Client: first mesh and decode rate"). No network,
// no set-up in the figure.
//
//   decode_rate FILE.mwv [--runs 9] [--setup-threads 1]
//
// Per run: a fresh ProgressiveDecoder from the container's header and its
// whole set-up (CompleteSetUp; wall time printed apart as set-up, with
// --setup-threads threads, beside the time Create took to return, after
// which a first mesh can be drawn; not in the rate), then every packet of
// the container in its order through AddPacket (CRC check and bitplane
// decoding; timed, thread CPU time and wall time), then one Mesh() (timed
// apart: the reconstruction a consumer asks for). Prints one line per run
// and the medians; 100 Mbit/s is 80 ns of CPU per payload byte.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "meshwave/container.h"
#include "meshwave/progressive_decoder.h"

namespace {

using meshwave::bench::Median;
using meshwave::bench::ThreadCpuSeconds;

double WallSeconds() {
  return std::chrono::duration<double>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: decode_rate FILE.mwv [--runs N] [--setup-threads N]\n");
    return 2;
  }
  int runs = 9;
  meshwave::DecoderOptions options;
  options.threads = 1;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--runs") runs = std::atoi(argv[i + 1]);
    if (std::string(argv[i]) == "--setup-threads") options.threads = std::atoi(argv[i + 1]);
  }
  // One sized read (istreambuf_iterator trips GCC 12's -Wnull-dereference).
  std::ifstream in(argv[1], std::ios::binary | std::ios::ate);
  std::string bytes(static_cast<size_t>(std::max<std::streamoff>(in.tellg(), 0)), '\0');
  in.seekg(0);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!in) {
    std::fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  auto parsed = meshwave::ParseContainer(bytes);
  if (!parsed.ok()) {
    std::fprintf(stderr, "%s: %s\n", argv[1], parsed.status().ToString().c_str());
    return 1;
  }
  uint64_t payload = 0;
  for (auto p : parsed->payloads) payload += p.size();
  std::vector<double> ns_per_byte, wall_ns_per_byte, mesh_ms, setup_ms, create_ms;
  for (int run = 0; run < runs; ++run) {
    const double setup0 = WallSeconds();
    auto decoder = meshwave::ProgressiveDecoder::Create(parsed->header, options);
    if (!decoder.ok()) {
      std::fprintf(stderr, "%s\n", decoder.status().ToString().c_str());
      return 1;
    }
    create_ms.push_back((WallSeconds() - setup0) * 1e3);
    (*decoder)->CompleteSetUp();
    setup_ms.push_back((WallSeconds() - setup0) * 1e3);
    const double cpu0 = ThreadCpuSeconds(), wall0 = WallSeconds();
    for (size_t i = 0; i < parsed->ids.size(); ++i) {
      const auto s = (*decoder)->AddPacket(parsed->ids[i], parsed->payloads[i]);
      if (!s.ok()) {
        std::fprintf(stderr, "%s\n", s.ToString().c_str());
        return 1;
      }
    }
    const double cpu1 = ThreadCpuSeconds(), wall1 = WallSeconds();
    const auto mesh = (*decoder)->Mesh();
    const double cpu2 = ThreadCpuSeconds();
    const double ns = (cpu1 - cpu0) * 1e9 / static_cast<double>(payload);
    const double wall_ns = (wall1 - wall0) * 1e9 / static_cast<double>(payload);
    std::printf(
        "run %d: set-up %.2f ms wall (Create %.2f ms); %zu packets, %llu payload bytes: decode %.2f ms CPU (%.1f "
        "ns/byte = %.1f Mbit/s), %.2f ms wall; Mesh() %.2f ms CPU (%zu "
        "vertices)\n",
        run, setup_ms.back(), create_ms.back(), parsed->ids.size(), static_cast<unsigned long long>(payload),
        (cpu1 - cpu0) * 1e3, ns, 8e3 / ns, (wall1 - wall0) * 1e3,
        (cpu2 - cpu1) * 1e3, mesh.positions.size());
    ns_per_byte.push_back(ns);
    wall_ns_per_byte.push_back(wall_ns);
    mesh_ms.push_back((cpu2 - cpu1) * 1e3);
  }
  const double ns = Median(ns_per_byte);
  const double best = *std::min_element(ns_per_byte.begin(), ns_per_byte.end());
  std::printf(
      "median: %.1f ns CPU per payload byte = %.1f Mbit/s on one core (best "
      "%.1f ns/byte; wall %.1f ns/byte); Mesh() %.2f ms CPU; set-up %.2f ms wall (%d "
      "threads; Create returned after %.2f ms)\n",
      ns, 8e3 / ns, best, Median(wall_ns_per_byte), Median(mesh_ms), Median(setup_ms),
      options.threads, Median(create_ms));
  return 0;
}
