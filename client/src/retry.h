// The client's one retry loop: a transfer that fails with an I/O error is
// tried again after BackoffDelay, as long as tries without progress stay
// below RetryPolicy::max_attempts. Session::Fetch and RegionSession::Fetch
// run their requests through it.
#ifndef MESHWAVE_CLIENT_RETRY_H_
#define MESHWAVE_CLIENT_RETRY_H_

#include <string>

#include "meshwave/client/backoff.h"
#include "meshwave/status.h"
#include "net.h"

namespace meshwave::client {

// Runs `step` (a callable returning net::awaitable<Result<bool>>: true
// when the work is done, false to run it again) until it is done or fails
// with anything but kIoError, which ends the loop with that status. After
// an I/O error it waits BackoffDelay(policy, n) before try n + 1 and counts
// the retry in `retries`; `mark()` (any comparable value) taken before and
// after a try tells whether it made progress, which starts the count of
// failures again. After max_attempts failures in a row: the last error,
// saying so; kIoError when the wait is interrupted.
template <typename Step, typename Mark>
net::awaitable<Status> RetryWithBackoff(net::any_io_executor executor, const RetryPolicy& policy,
                                        int& retries, Step step, Mark mark) {
  int failures = 0;
  net::steady_timer timer(executor);
  for (;;) {
    const auto before = mark();
    Result<bool> done = co_await step();
    if (done.ok()) {
      if (*done) co_return Status::Ok();
      continue;
    }
    if (done.status().code() != StatusCode::kIoError) co_return done.status();
    // A transfer that delivered something starts the count again.
    if (mark() != before) failures = 0;
    if (++failures >= policy.max_attempts) {
      co_return done.status().WithContext("gave up after " + std::to_string(failures) +
                                          " attempts");
    }
    ++retries;
    timer.expires_after(BackoffDelay(policy, failures));
    auto [ec] = co_await timer.async_wait(net::as_tuple(net::use_awaitable));
    if (ec) co_return IoError("interrupted while waiting to retry");
  }
}

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_RETRY_H_
