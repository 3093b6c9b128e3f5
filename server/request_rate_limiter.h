// Per-client request-rate limiting: one token bucket per client address
// (requests per second, with a burst), so that one client flooding the
// server with requests gets 429 while others are served. Thread-safe; the
// table of clients is bounded (idle clients are forgotten first).
#ifndef MESHWAVE_SERVER_REQUEST_RATE_LIMITER_H_
#define MESHWAVE_SERVER_REQUEST_RATE_LIMITER_H_

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_map>

namespace meshwave::server {

class RequestRateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  // `rate` requests per second per client, 0: no limit. `burst`: requests a
  // client may send at once after being idle (at least 1).
  RequestRateLimiter(uint32_t rate, uint32_t burst, size_t max_clients = 100000);

  // True when `client` may make a request now (it is then counted).
  bool Allow(const std::string& client, Clock::time_point now = Clock::now());
  size_t clients() const;

 private:
  struct Bucket {
    double tokens = 0;
    Clock::time_point last;
  };
  void Prune(Clock::time_point now);

  const double rate_;
  const double burst_;
  const size_t max_clients_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_REQUEST_RATE_LIMITER_H_
