#include "lazy_deadline.h"

namespace meshwave::server {

void LazyDeadline::ExpiresAt(Clock::time_point at) {
  deadline_ = at;
  // A wait that ends no later than the deadline re-arms itself for the rest.
  if (waiting_ && armed_ <= at) return;
  Arm(at);
}

void LazyDeadline::Cancel() {
  deadline_ = Clock::time_point::max();
  waiting_ = false;
  timer_.cancel();
}

void LazyDeadline::Arm(Clock::time_point at) {
  // expires_at cancels a pending wait, whose handler then sees
  // operation_aborted and does nothing.
  timer_.expires_at(at);
  armed_ = at;
  waiting_ = true;
  ++arms_;
  timer_.async_wait([this, owner = owner_](beast::error_code ec) {
    // The connection may be gone, and `this` with it; else it stays alive
    // while its deadline is handled.
    if (auto alive = owner.lock()) OnTimer(ec);
  });
}

void LazyDeadline::OnTimer(beast::error_code ec) {
  if (ec) return;  // re-armed or cancelled
  waiting_ = false;
  if (deadline_ == Clock::time_point::max()) return;
  if (Clock::now() < deadline_) return Arm(deadline_);
  deadline_ = Clock::time_point::max();
  if (on_expiry_) on_expiry_();
}

}  // namespace meshwave::server
