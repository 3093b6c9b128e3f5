// Retries of a failed request: how many, and how long to wait before each.
#ifndef MESHWAVE_CLIENT_BACKOFF_H_
#define MESHWAVE_CLIENT_BACKOFF_H_

#include <chrono>

namespace meshwave::client {

struct RetryPolicy {
  // Tries of one request without progress, the first one included; a
  // request that delivered at least one packet resets the count.
  int max_attempts = 6;
  std::chrono::milliseconds initial_delay{100};
  std::chrono::milliseconds max_delay{4000};
  double multiplier = 2;
};

// The wait before retry number `retry` (1 for the first retry):
// initial_delay · multiplier^(retry-1), at most max_delay; zero for retry < 1.
std::chrono::milliseconds BackoffDelay(const RetryPolicy& policy, int retry);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_BACKOFF_H_
