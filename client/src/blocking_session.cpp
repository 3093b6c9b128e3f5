#include "meshwave/client/blocking_session.h"

#include "net.h"

namespace meshwave::client {

BlockingSession::BlockingSession(const MeshUrl& url,
                                 const SessionOptions& options,
                                 const TransportOptions& transport_options)
    : io_(std::make_unique<net::io_context>(1)) {
  session_ = std::make_unique<Session>(
      MakeHttpTransport(io_->get_executor(), url, transport_options), options);
}

BlockingSession::~BlockingSession() {
  session_.reset();  // its sockets before their io_context
}

Status BlockingSession::Fetch(const Budget& budget,
                              const ProgressHandler& on_progress) {
  Status result(StatusCode::kInternal, "the fetch did not finish");
  session_->AsyncFetch(budget, on_progress,
                       [&result](Status s) { result = std::move(s); });
  io_->restart();
  io_->run();
  return result;
}

}  // namespace meshwave::client
