#include "meshwave/client/blocking_session.h"

#include "net.h"
#include "run_to_completion.h"

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
  return RunToCompletion(*io_, session_->Fetch(budget, on_progress));
}

}  // namespace meshwave::client
