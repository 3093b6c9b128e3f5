// BlockingSession: a Session with its own io_context, for callers that want
// a plain function call (the CLI, scripts). Fetch runs on the calling
// thread until the budget is reached or the fetch fails.
#ifndef MESHWAVE_CLIENT_BLOCKING_SESSION_H_
#define MESHWAVE_CLIENT_BLOCKING_SESSION_H_

#include <memory>

#include "meshwave/client/session.h"
#include "meshwave/client/url.h"

namespace boost::asio {
class io_context;
}

namespace meshwave::client {

class BlockingSession {
 public:
  // A session for the mesh at `url` over the transport its scheme names
  // (MakeTransport); nothing is sent yet.
  BlockingSession(const MeshUrl& url, const SessionOptions& options,
                  const TransportOptions& transport_options);
  ~BlockingSession();

  Status Fetch(const Budget& budget, const ProgressHandler& on_progress = {});
  Session& session() { return *session_; }
  const Session& session() const { return *session_; }

 private:
  std::unique_ptr<boost::asio::io_context>
      io_;  // outlives the session's sockets
  std::unique_ptr<Session> session_;
};

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_BLOCKING_SESSION_H_
