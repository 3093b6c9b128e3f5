#include "metrics.h"

#include <algorithm>
#include <cstdio>

namespace meshwave::server {

void Metrics::RecordRequest(unsigned status, uint64_t bytes, double seconds) {
  // Relaxed: counters, read together only by Render. One bucket per
  // request (Render makes them cumulative): incrementing every bucket at or
  // above the duration was 12 contended atomic additions per fast request.
  constexpr auto kRelaxed = std::memory_order_relaxed;
  if (status < by_code_.size()) by_code_[status].fetch_add(1, kRelaxed);
  bytes_sent_.fetch_add(bytes, kRelaxed);
  count_.fetch_add(1, kRelaxed);
  micros_sum_.fetch_add(static_cast<uint64_t>(seconds * 1e6), kRelaxed);
  const auto bucket = std::lower_bound(kBuckets.begin(), kBuckets.end(), seconds);
  if (bucket != kBuckets.end()) buckets_[static_cast<size_t>(bucket - kBuckets.begin())].fetch_add(1, kRelaxed);
}

std::string Metrics::Render(uint64_t catalog_meshes, uint64_t open_containers) const {
  std::string out;
  char line[256];
  auto add = [&](const char* text) { out += text; };
  add("# HELP meshwave_http_requests_total HTTP requests answered, by status code.\n"
      "# TYPE meshwave_http_requests_total counter\n");
  for (size_t code = 100; code < by_code_.size(); ++code) {
    const uint64_t n = by_code_[code].load();
    if (n == 0) continue;
    std::snprintf(line, sizeof line, "meshwave_http_requests_total{code=\"%zu\"} %llu\n",
                  code, static_cast<unsigned long long>(n));
    add(line);
  }
  add("# HELP meshwave_http_response_bytes_total Bytes written in responses.\n"
      "# TYPE meshwave_http_response_bytes_total counter\n");
  std::snprintf(line, sizeof line, "meshwave_http_response_bytes_total %llu\n",
                static_cast<unsigned long long>(bytes_sent_.load()));
  add(line);
  add("# HELP meshwave_http_request_duration_seconds From request header to response written.\n"
      "# TYPE meshwave_http_request_duration_seconds histogram\n");
  // Read after the buckets (RecordRequest counts first): +Inf is never
  // below the last finite bucket.
  uint64_t cumulative = 0;
  for (size_t i = 0; i < kBuckets.size(); ++i) {
    cumulative += buckets_[i].load();
    std::snprintf(line, sizeof line,
                  "meshwave_http_request_duration_seconds_bucket{le=\"%g\"} %llu\n",
                  kBuckets[i], static_cast<unsigned long long>(cumulative));
    add(line);
  }
  // One line per snprintf: the three together overflowed `line` and lost
  // the _count line (and the end of _sum) once the numbers grew.
  const auto count = static_cast<unsigned long long>(std::max<uint64_t>(count_.load(), cumulative));
  std::snprintf(line, sizeof line, "meshwave_http_request_duration_seconds_bucket{le=\"+Inf\"} %llu\n",
                count);
  add(line);
  std::snprintf(line, sizeof line, "meshwave_http_request_duration_seconds_sum %.6f\n",
                static_cast<double>(micros_sum_.load()) * 1e-6);
  add(line);
  std::snprintf(line, sizeof line, "meshwave_http_request_duration_seconds_count %llu\n", count);
  add(line);
  std::snprintf(line, sizeof line,
                "# HELP meshwave_catalog_meshes Meshes in the catalog.\n"
                "# TYPE meshwave_catalog_meshes gauge\n"
                "meshwave_catalog_meshes %llu\n",
                static_cast<unsigned long long>(catalog_meshes));
  add(line);
  std::snprintf(line, sizeof line,
                "# HELP meshwave_open_containers Containers memory-mapped.\n"
                "# TYPE meshwave_open_containers gauge\n"
                "meshwave_open_containers %llu\n",
                static_cast<unsigned long long>(open_containers));
  add(line);
  std::snprintf(line, sizeof line,
                "# HELP meshwave_http_connections Open HTTP connections.\n"
                "# TYPE meshwave_http_connections gauge\n"
                "meshwave_http_connections %lld\n",
                static_cast<long long>(connections_.load()));
  add(line);
  add("# HELP meshwave_websocket_connections Open WebSocket sessions.\n"
      "# TYPE meshwave_websocket_connections gauge\n");
  std::snprintf(line, sizeof line, "meshwave_websocket_connections %lld\n",
                static_cast<long long>(websocket_connections_.load()));
  add(line);
  add("# HELP meshwave_websocket_sent_bytes_total Bytes of WebSocket messages sent.\n"
      "# TYPE meshwave_websocket_sent_bytes_total counter\n");
  std::snprintf(line, sizeof line, "meshwave_websocket_sent_bytes_total %llu\n",
                static_cast<unsigned long long>(websocket_bytes_sent_.load()));
  add(line);
  return out;
}

}  // namespace meshwave::server
