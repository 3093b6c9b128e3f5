#include "token_bucket.h"

#include <algorithm>
#include <cmath>

namespace meshwave::server {

TokenBucket::TokenBucket(uint64_t rate, Clock::time_point now,
                         Clock::duration burst)
    : rate_(rate),
      max_credit_(static_cast<double>(rate) *
                  std::chrono::duration<double>(burst).count()),
      last_(now) {}

void TokenBucket::Refill(Clock::time_point now) {
  if (now <= last_) return;
  const double seconds = std::chrono::duration<double>(now - last_).count();
  tokens_ =
      std::min(max_credit_, tokens_ + seconds * static_cast<double>(rate_));
  last_ = now;
}

TokenBucket::Clock::duration TokenBucket::Take(uint64_t bytes,
                                               Clock::time_point now) {
  Refill(now);
  if (tokens_ < 0) {
    const double seconds = -tokens_ / static_cast<double>(rate_);
    // Rounded up, at least 1 us: the caller must not spin.
    return std::max<Clock::duration>(
        std::chrono::microseconds(1),
        std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(std::ceil(seconds * 1e6) * 1e-6)));
  }
  tokens_ -= static_cast<double>(bytes);
  return Clock::duration::zero();
}

void TokenBucket::DropCredit(Clock::time_point now) {
  Refill(now);
  tokens_ = std::min(tokens_, 0.0);
}

}  // namespace meshwave::server
