// first_mesh: time to first mesh and decode throughput of the client
// library against a running meshwave-server (bench/first_mesh.sh starts one).
//
//   first_mesh URL [--runs 9] [--pace BYTES_PER_S]
//
// Per run, a fresh BlockingSession (new connection) fetches the whole
// stream; the clock starts before the session is made and stops for the
// first mesh when the first progress callback (the base mesh, from the
// header) has materialised decoder.Mesh(). From there to the end of the
// fetch the same thread receives, CRC-checks and decodes every packet: the
// packets' bytes over that time is the rate the client keeps up with.
// Prints one line per run and the medians.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "meshwave/client/blocking_session.h"

namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

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
  std::vector<double> first_ms, total_ms, mbit_s, packet_mbit_s;
  for (int run = 0; run < runs; ++run) {
    meshwave::client::TransportOptions transport;
    transport.pace_bytes_per_second = pace;
    const auto t0 = Clock::now();
    meshwave::client::BlockingSession blocking(
        *url, meshwave::client::SessionOptions{}, transport);
    double first = -1;
    size_t vertices = 0;
    const auto status = blocking.Fetch(
        meshwave::client::Budget::All(),
        [&](const meshwave::client::Progress&,
            const meshwave::ProgressiveDecoder& decoder) {
          if (first >= 0) return;
          vertices = decoder.Mesh().positions.size();
          first = std::chrono::duration<double, std::milli>(Clock::now() - t0)
                      .count();
        });
    const double total =
        std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    if (!status.ok()) {
      std::fprintf(stderr, "%s\n", status.ToString().c_str());
      return 1;
    }
    const auto p = blocking.session().progress();
    const double rate = static_cast<double>(p.bytes) * 8 / (total * 1e3);
    const uint64_t payload =
        p.bytes - blocking.session().decoder()->header().ByteSizeLong();
    const double packet_rate =
        static_cast<double>(payload) * 8 / ((total - first) * 1e3);
    std::printf(
        "run %d: first mesh %.2f ms (%zu vertices); whole stream %llu bytes, "
        "%zu packets in %.1f ms = %.1f Mbit/s; after the first mesh %.1f "
        "Mbit/s\n",
        run, first, vertices, static_cast<unsigned long long>(p.bytes),
        p.packets, total, rate, packet_rate);
    first_ms.push_back(first);
    total_ms.push_back(total);
    mbit_s.push_back(rate);
    packet_mbit_s.push_back(packet_rate);
  }
  std::printf(
      "median: first mesh %.2f ms, whole stream %.1f ms = %.1f Mbit/s, "
      "packets after the first mesh %.1f Mbit/s\n",
      Median(first_ms), Median(total_ms), Median(mbit_s),
      Median(packet_mbit_s));
  return 0;
}
