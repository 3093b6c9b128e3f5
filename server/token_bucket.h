// Paces a stream to a byte rate: a token bucket that may run into debt, so
// a packet larger than the bucket still goes out and the average rate holds
// whatever the packet sizes. Pure arithmetic on time points given by the
// caller (a steady_timer waits for the delay it returns); not thread-safe.
#ifndef MESHWAVE_SERVER_TOKEN_BUCKET_H_
#define MESHWAVE_SERVER_TOKEN_BUCKET_H_

#include <chrono>
#include <cstdint>

namespace meshwave::server {

class TokenBucket {
 public:
  using Clock = std::chrono::steady_clock;

  // `rate` bytes per second (> 0). Credit saved while a timer fires late is
  // capped at `burst` of sending time: enough to catch up a loaded event
  // loop, not enough to send a long burst after an idle period.
  TokenBucket(uint64_t rate, Clock::time_point now,
              Clock::duration burst = std::chrono::milliseconds(200));

  // Zero when `bytes` may be sent now (then they are charged), else how
  // long to wait before asking again.
  Clock::duration Take(uint64_t bytes, Clock::time_point now);
  // Forgets credit saved while idle (before a new request), keeps any debt.
  void DropCredit(Clock::time_point now);
  uint64_t rate() const { return rate_; }

 private:
  void Refill(Clock::time_point now);

  uint64_t rate_;
  double max_credit_;
  double tokens_ = 0;  // bytes; negative: debt to wait off
  Clock::time_point last_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_TOKEN_BUCKET_H_
