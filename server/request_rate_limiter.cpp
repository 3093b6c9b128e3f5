#include "request_rate_limiter.h"

#include <algorithm>

namespace meshwave::server {

RequestRateLimiter::RequestRateLimiter(uint32_t rate, uint32_t burst, size_t max_clients)
    : rate_(rate), burst_(std::max<uint32_t>(burst, 1)), max_clients_(std::max<size_t>(max_clients, 1)) {}

bool RequestRateLimiter::Allow(const std::string& client, Clock::time_point now) {
  if (rate_ <= 0) return true;
  std::lock_guard lock(mutex_);
  auto it = buckets_.find(client);
  if (it == buckets_.end()) {
    if (buckets_.size() >= max_clients_) Prune(now);
    it = buckets_.emplace(client, Bucket{burst_, now}).first;
  }
  Bucket& b = it->second;
  const double elapsed = std::chrono::duration<double>(now - b.last).count();
  b.tokens = std::min(burst_, b.tokens + std::max(elapsed, 0.0) * rate_);
  b.last = now;
  if (b.tokens < 1) return false;
  b.tokens -= 1;
  return true;
}

size_t RequestRateLimiter::clients() const {
  std::lock_guard lock(mutex_);
  return buckets_.size();
}

void RequestRateLimiter::Prune(Clock::time_point now) {
  // A bucket that has refilled completely carries no state worth keeping.
  const auto full = std::chrono::duration<double>(burst_ / rate_);
  std::erase_if(buckets_, [&](const auto& kv) { return now - kv.second.last >= full; });
  // Still full (that many clients active at once): start over rather than
  // grow without bound; the flooders are limited again from their burst.
  if (buckets_.size() >= max_clients_) buckets_.clear();
}

}  // namespace meshwave::server
