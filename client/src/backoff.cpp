#include "meshwave/client/backoff.h"

#include <algorithm>
#include <cmath>

namespace meshwave::client {

std::chrono::milliseconds BackoffDelay(const RetryPolicy& policy, int retry) {
  if (retry < 1) return std::chrono::milliseconds(0);
  // In double, so that large retry numbers saturate instead of overflowing.
  const double ms = static_cast<double>(policy.initial_delay.count()) *
                    std::pow(std::max(policy.multiplier, 1.0), retry - 1);
  const double capped =
      std::min(ms, static_cast<double>(policy.max_delay.count()));
  return std::chrono::milliseconds(static_cast<int64_t>(std::max(capped, 0.0)));
}

}  // namespace meshwave::client
