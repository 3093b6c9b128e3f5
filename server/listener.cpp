#include "listener.h"

#include <spdlog/spdlog.h>

#include "http_session.h"

namespace meshwave::server {

namespace {

net::any_io_executor AcceptorExecutor(net::io_context& ioc, bool shared) {
  if (shared) return net::make_strand(ioc);
  return ioc.get_executor();
}

}  // namespace

Listener::Listener(std::vector<net::io_context*> contexts, bool shared, ServerContext& ctx)
    : contexts_(std::move(contexts)),
      shared_(shared),
      acceptor_(AcceptorExecutor(*contexts_.front(), shared)),
      ctx_(ctx) {}

Result<std::shared_ptr<Listener>> Listener::Create(std::vector<net::io_context*> contexts,
                                                   bool shared, tcp::endpoint endpoint,
                                                   ServerContext& ctx) {
  if (contexts.empty()) return InvalidArgument("the listener needs an io_context");
  std::shared_ptr<Listener> l(new Listener(std::move(contexts), shared, ctx));
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

net::any_io_executor Listener::NextExecutor() {
  // Several threads on one io_context: a strand per connection. Else the
  // connection's thread alone runs its handlers, no strand needed.
  if (shared_) return net::make_strand(*contexts_.front());
  net::io_context& ioc = *contexts_[next_];
  next_ = (next_ + 1) % contexts_.size();
  return ioc.get_executor();
}

void Listener::DoAccept() {
  acceptor_.async_accept(NextExecutor(),
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
