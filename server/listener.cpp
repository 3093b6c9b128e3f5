#include "listener.h"

#include <spdlog/spdlog.h>

#include "http_session.h"

namespace meshwave::server {

Listener::Listener(net::io_context& ioc, ServerContext& ctx)
    : ioc_(ioc), acceptor_(net::make_strand(ioc)), ctx_(ctx) {}

Result<std::shared_ptr<Listener>> Listener::Create(net::io_context& ioc, tcp::endpoint endpoint,
                                                   ServerContext& ctx) {
  std::shared_ptr<Listener> l(new Listener(ioc, ctx));
  beast::error_code ec;
  auto fail = [&](const char* what) {
    return IoError(std::string("cannot ") + what + " " + endpoint.address().to_string() + ":" +
                   std::to_string(endpoint.port()) + ": " + ec.message());
  };
  l->acceptor_.open(endpoint.protocol(), ec);
  if (ec) return fail("open");
  l->acceptor_.set_option(net::socket_base::reuse_address(true), ec);
  if (ec) return fail("set options on");
  l->acceptor_.bind(endpoint, ec);
  if (ec) return fail("bind");
  l->acceptor_.listen(net::socket_base::max_listen_connections, ec);
  if (ec) return fail("listen on");
  l->port_ = l->acceptor_.local_endpoint(ec).port();
  if (ec) return fail("read the port of");
  return l;
}

void Listener::Run() { DoAccept(); }

void Listener::Stop() {
  net::post(acceptor_.get_executor(), [self = shared_from_this()] {
    beast::error_code ec;
    self->acceptor_.close(ec);
  });
}

void Listener::DoAccept() {
  acceptor_.async_accept(net::make_strand(ioc_),
                         beast::bind_front_handler(&Listener::OnAccept, shared_from_this()));
}

void Listener::OnAccept(beast::error_code ec, tcp::socket socket) {
  if (ec == net::error::operation_aborted || !acceptor_.is_open()) return;  // stopped
  if (ec) {
    // Out of descriptors and the like: keep accepting, the next may work.
    spdlog::warn("accept: {}", ec.message());
  } else {
    beast::error_code opt_ec;
    // Packets are sent as soon as written: no Nagle delay on small frames.
    socket.set_option(tcp::no_delay(true), opt_ec);
    const bool over = ctx_.metrics().connections() >=
                      static_cast<int64_t>(ctx_.config().max_connections());
    auto session = std::make_shared<HttpSession>(std::move(socket), ctx_, over);
    ctx_.Register(session);
    session->Run();
  }
  DoAccept();
}

}  // namespace meshwave::server
