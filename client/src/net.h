// Short names for Boost.Asio and Boost.Beast, and their headers.
#ifndef MESHWAVE_CLIENT_NET_H_
#define MESHWAVE_CLIENT_NET_H_

// GCC 12 at -O3 reports -Wnull-dereference inside Asio's scheduler and
// strand code once it is inlined (false positives, as in server/net.h).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <boost/asio.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#pragma GCC diagnostic pop

namespace meshwave::client {

namespace net = boost::asio;
namespace ssl = boost::asio::ssl;
namespace beast = boost::beast;
namespace http = boost::beast::http;
using tcp = boost::asio::ip::tcp;

// The completion token of every awaited operation here: co_await gives
// (error_code, result...) instead of throwing.
inline auto Tuple() { return net::as_tuple(net::use_awaitable); }

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_NET_H_
