// Short names for the Boost.Asio and Boost.Beast namespaces.
#ifndef MESHWAVE_SERVER_NET_H_
#define MESHWAVE_SERVER_NET_H_

// GCC 12 at -O3 reports -Wnull-dereference inside Asio's scheduler and
// strand code once it is inlined into ours: false positives on pointers
// the run loop always sets. Silenced for these headers only (the state is
// attached to their source lines).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#pragma GCC diagnostic pop

namespace meshwave::server {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = boost::beast::http;
using tcp = boost::asio::ip::tcp;

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_NET_H_
