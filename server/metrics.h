// Server counters, exported in the Prometheus text format at /metrics.
// Lock-free: every field is an atomic updated by the io threads.
#ifndef MESHWAVE_SERVER_METRICS_H_
#define MESHWAVE_SERVER_METRICS_H_

#include <array>
#include <atomic>
#include <cstdint>
#include <string>

namespace meshwave::server {

class Metrics {
 public:
  // One answered request: its status code, the bytes written for it and
  // the time from its header to the end of the write.
  void RecordRequest(unsigned status, uint64_t bytes, double seconds);
  void ConnectionOpened() { ++connections_; }
  void ConnectionClosed() { --connections_; }
  int64_t connections() const { return connections_.load(); }
  void WebSocketOpened() { ++websocket_connections_; }
  void WebSocketClosed() { --websocket_connections_; }
  int64_t websocket_connections() const { return websocket_connections_.load(); }
  void AddWebSocketBytes(uint64_t bytes) { websocket_bytes_sent_ += bytes; }

  // The exposition text; gauges read elsewhere are passed in.
  std::string Render(uint64_t catalog_meshes, uint64_t open_containers) const;

 private:
  // Upper bounds of the latency buckets, seconds.
  static constexpr std::array<double, 12> kBuckets = {
      0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 5};
  std::array<std::atomic<uint64_t>, 600> by_code_{};
  // Requests whose duration fell in (kBuckets[i-1], kBuckets[i]].
  std::array<std::atomic<uint64_t>, kBuckets.size()> buckets_{};
  std::atomic<uint64_t> count_{0};
  std::atomic<uint64_t> micros_sum_{0};
  std::atomic<uint64_t> bytes_sent_{0};
  std::atomic<int64_t> connections_{0};
  std::atomic<int64_t> websocket_connections_{0};
  std::atomic<uint64_t> websocket_bytes_sent_{0};
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_METRICS_H_
