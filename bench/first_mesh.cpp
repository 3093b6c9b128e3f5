// first_mesh: time to first mesh and decode throughput of the client
// library against a running meshwave-server (bench/first_mesh.sh starts one).
//
//   first_mesh URL [--runs 9] [--pace BYTES_PER_S]
//
// Per run, a fresh BlockingSession (new connection) fetches the whole
// stream; the clock starts before the session is made and stops for the
// first mesh when the first progress callback (the header) has materialised
// the mesh the browser viewer and `meshwave decode` draw: the level one
// past the finest with detail (level 1 before any packet). From there to the end of the
// fetch the same thread receives, CRC-checks and decodes every packet: the
// packets' bytes over that time is the rate the client keeps up with; the
// thread's CPU time over the same span, per payload byte, is what it costs
// (100 Mbit/s = 80 ns per byte). With --pace the server sends at that rate,
// so the last byte cannot arrive before start + bytes / rate: the lag is the
// time from then to the end of the fetch (an upper bound: the stream starts
// after connect and upgrade).
// Prints one line per run and the medians.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "meshwave/client/blocking_session.h"

namespace {

using Clock = std::chrono::steady_clock;

using meshwave::bench::Median;

double ThreadCpuMs() { return meshwave::bench::ThreadCpuSeconds() * 1e3; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: first_mesh URL [--runs N] [--pace B/s]\n");
    return 2;
  }
  const std::string url_text = argv[1];
  int runs = 9;
  uint64_t pace = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string k = argv[i];
    if (k == "--runs") runs = std::atoi(argv[i + 1]);
    if (k == "--pace") pace = std::strtoull(argv[i + 1], nullptr, 10);
  }
  auto url = meshwave::client::ParseMeshUrl(url_text);
  if (!url.ok()) {
    std::fprintf(stderr, "%s\n", url.status().ToString().c_str());
    return 2;
  }
  std::vector<double> first_ms, total_ms, mbit_s, packet_mbit_s, cpu_ns,
      lag_ms, decode_lag_ms;
  for (int run = 0; run < runs; ++run) {
    meshwave::client::TransportOptions transport;
    transport.pace_bytes_per_second = pace;
    const auto t0 = Clock::now();
    meshwave::client::BlockingSession blocking(
        *url, meshwave::client::SessionOptions{}, transport);
    double first = -1, first_cpu = 0;
    size_t vertices = 0;
    const auto status = blocking.Fetch(
        meshwave::client::Budget::All(),
        [&](const meshwave::client::Progress&,
            const meshwave::ProgressiveDecoder& decoder) {
          if (first >= 0) return;
          const int levels = static_cast<int>(decoder.header().transform.levels);
          vertices = decoder.Mesh(std::min(levels, decoder.DetailLevels() + 1))
                         .positions.size();
          first = std::chrono::duration<double, std::milli>(Clock::now() - t0)
                      .count();
          first_cpu = ThreadCpuMs();
        });
    const double total =
        std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const double cpu = ThreadCpuMs() - first_cpu;
    // The final mesh, as a consumer would ask for it once the fetch ends.
    const size_t final_vertices =
        status.ok() ? blocking.session().decoder()->Mesh().positions.size() : 0;
    const double final_mesh =
        std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!status.ok()) {
      std::fprintf(stderr, "%s\n", status.ToString().c_str());
      return 1;
    }
    const auto p = blocking.session().progress();
    const double rate = static_cast<double>(p.bytes) * 8 / (total * 1e3);
    const meshwave::ProgressiveDecoder& decoder = *blocking.session().decoder();
    uint64_t payload = 0;
    for (uint32_t id = 0; id < decoder.packet_count(); ++id) {
      if (decoder.HasPacket(id)) payload += decoder.header().packets.length[id];
    }
    const double packet_rate =
        static_cast<double>(payload) * 8 / ((total - first) * 1e3);
    const double ns_per_byte = cpu * 1e6 / static_cast<double>(payload);
    // The server paces what it sends on the wire: the header and payloads.
    const double paced_end =
        pace > 0 ? static_cast<double>(p.received_bytes) * 1e3 /
                       static_cast<double>(pace)
                 : 0;
    const double decode_lag = total - paced_end;
    const double lag = final_mesh - paced_end;
    std::printf(
        "run %d: first mesh %.2f ms (%zu vertices); whole stream %llu bytes, "
        "%zu packets in %.1f ms = %.1f Mbit/s; after the first mesh %.1f "
        "Mbit/s, client CPU %.1f ns per payload byte",
        run, first, vertices, static_cast<unsigned long long>(p.bytes),
        p.packets, total, rate, packet_rate, ns_per_byte);
    std::printf("; final mesh (%zu vertices) at %.1f ms", final_vertices,
                final_mesh);
    if (pace > 0) {
      std::printf(
          "; last packet decoded %.1f ms and final mesh %.1f ms after the "
          "paced last byte (%.1f ms)",
          decode_lag, lag, paced_end);
    }
    std::printf("\n");
    first_ms.push_back(first);
    total_ms.push_back(total);
    mbit_s.push_back(rate);
    packet_mbit_s.push_back(packet_rate);
    cpu_ns.push_back(ns_per_byte);
    lag_ms.push_back(lag);
    decode_lag_ms.push_back(decode_lag);
  }
  std::printf(
      "median: first mesh %.2f ms, whole stream %.1f ms = %.1f Mbit/s, "
      "packets after the first mesh %.1f Mbit/s, client CPU %.1f ns per "
      "payload byte (= %.1f Mbit/s)",
      Median(first_ms), Median(total_ms), Median(mbit_s),
      Median(packet_mbit_s), Median(cpu_ns), 8e3 / Median(cpu_ns));
  if (pace > 0) {
    std::printf(
        "; after the paced last byte: last packet decoded %.1f ms, final "
        "mesh %.1f ms",
        Median(decode_lag_ms), Median(lag_ms));
  }
  std::printf("\n");
  return 0;
}
