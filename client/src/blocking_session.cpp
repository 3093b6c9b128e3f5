#include "meshwave/client/blocking_session.h"

#include "net.h"

namespace meshwave::client {

BlockingSession::BlockingSession(const MeshUrl& url,
                                 const SessionOptions& options,
                                 const TransportOptions& transport_options)
    : io_(std::make_unique<net::io_context>(1)) {
  session_ = std::make_unique<Session>(
      MakeTransport(io_->get_executor(), url, transport_options), options);
}

BlockingSession::~BlockingSession() {
  session_.reset();  // its sockets before their io_context
}

Status BlockingSession::Fetch(const Budget& budget,
                              const ProgressHandler& on_progress) {
  Status result(StatusCode::kInternal, "the fetch did not finish");
  bool finished = false;
  session_->AsyncFetch(budget, on_progress, [&](Status s) {
    result = std::move(s);
    finished = true;
  });
  io_->restart();
  // Until the fetch ends, not until the io_context runs dry: a WebSocket
  // kept open for the next Fetch has its idle timer pending.
  while (!finished && io_->run_one() > 0) {
  }
  return result;
}

}  // namespace meshwave::client
