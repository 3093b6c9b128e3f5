// A connection's deadline on one steady_timer that is not re-armed for every
// read and write. Moving the deadline later only records it: the timer,
// when it fires before the recorded deadline, waits again for the rest.
// Only a deadline earlier than the armed expiry re-arms the timer at once.
// A keep-alive connection answering requests back to back thus costs one
// timer wait per timeout period instead of one per read and per write
// (Beast's tcp_stream::expires_after). Use it on the connection's executor
// (its thread, or its strand): it is not thread-safe.
#ifndef MESHWAVE_SERVER_LAZY_DEADLINE_H_
#define MESHWAVE_SERVER_LAZY_DEADLINE_H_

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

#include "net.h"

namespace meshwave::server {

class LazyDeadline {
 public:
  using Clock = std::chrono::steady_clock;

  explicit LazyDeadline(const net::any_io_executor& executor) : timer_(executor) {}

  // `on_expiry` runs on the executor when a deadline passes, unless `owner`
  // has died by then (the timer's waits hold `owner` weakly, so a pending
  // deadline never keeps a finished connection alive).
  void Bind(std::weak_ptr<void> owner, std::function<void()> on_expiry) {
    owner_ = std::move(owner);
    on_expiry_ = std::move(on_expiry);
  }

  void ExpiresAfter(Clock::duration d) { ExpiresAt(Clock::now() + d); }
  void ExpiresAt(Clock::time_point at);
  // No deadline: an armed wait fires and finds nothing due.
  void ExpiresNever() { deadline_ = Clock::time_point::max(); }
  // No deadline and no wait left (the socket is handed to another owner).
  void Cancel();

  Clock::time_point deadline() const { return deadline_; }
  // How many times the timer was armed (tests, benchmarks).
  uint64_t arms() const { return arms_; }

 private:
  void Arm(Clock::time_point at);
  void OnTimer(beast::error_code ec);

  net::steady_timer timer_;
  std::weak_ptr<void> owner_;
  std::function<void()> on_expiry_;
  Clock::time_point deadline_ = Clock::time_point::max();
  Clock::time_point armed_ = Clock::time_point::max();  // the pending wait's expiry
  bool waiting_ = false;
  uint64_t arms_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_LAZY_DEADLINE_H_
