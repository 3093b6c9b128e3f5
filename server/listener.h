// Accepts connections and starts an HttpSession on a strand for each, with
// TCP_NODELAY set; past the connection cap a session only answers 503.
#ifndef MESHWAVE_SERVER_LISTENER_H_
#define MESHWAVE_SERVER_LISTENER_H_

#include <memory>

#include "meshwave/status.h"
#include "net.h"
#include "server_context.h"

namespace meshwave::server {

class Listener : public std::enable_shared_from_this<Listener> {
 public:
  // Binds and listens; IoError naming the endpoint when it cannot.
  static Result<std::shared_ptr<Listener>> Create(net::io_context& ioc, tcp::endpoint endpoint,
                                                  ServerContext& ctx);
  uint16_t port() const { return port_; }
  void Run();
  // Stops accepting (thread-safe).
  void Stop();

 private:
  Listener(net::io_context& ioc, ServerContext& ctx);
  void DoAccept();
  void OnAccept(beast::error_code ec, tcp::socket socket);

  net::io_context& ioc_;
  tcp::acceptor acceptor_;
  ServerContext& ctx_;
  uint16_t port_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_LISTENER_H_
