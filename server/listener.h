// Accepts connections and starts an HttpSession for each, with TCP_NODELAY
// set; past the connection cap a session only answers 503. Connections go
// round-robin to the io_contexts given (one per io thread), or, with a
// single shared io_context, each to a strand of it.
#ifndef MESHWAVE_SERVER_LISTENER_H_
#define MESHWAVE_SERVER_LISTENER_H_

#include <memory>
#include <vector>

#include "meshwave/status.h"
#include "net.h"
#include "server_context.h"

namespace meshwave::server {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Binds and listens; IoError naming the endpoint when it cannot.
  // `contexts`: one per io thread, each run by that thread alone; or one
  // run by several threads, when `shared` (sessions then get strands).
  static Result<std::shared_ptr<Listener>> Create(std::vector<net::io_context*> contexts,
                                                  bool shared, tcp::endpoint endpoint,
                                                  ServerContext& ctx);
  uint16_t port() const { return port_; }
  void Run();
  // Stops accepting (thread-safe).
  void Stop();

 private:
  Listener(std::vector<net::io_context*> contexts, bool shared, ServerContext& ctx);
  net::any_io_executor NextExecutor();
  void DoAccept();
  void OnAccept(beast::error_code ec, tcp::socket socket);

  const std::vector<net::io_context*> contexts_;
  const bool shared_;
  size_t next_ = 0;  // round-robin over contexts_
  tcp::acceptor acceptor_;
  ServerContext& ctx_;
  uint16_t port_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_LISTENER_H_
