// Opening a connection to a meshwave-server and reading its refusals:
// resolve and connect with a timeout, TLS with certificate and host name
// verification, and the status a refusal maps to. Shared by the HTTP and
// WebSocket transports so both check certificates the same way.
#ifndef MESHWAVE_CLIENT_SERVER_CONNECTION_H_
#define MESHWAVE_CLIENT_SERVER_CONNECTION_H_

#include <memory>
#include <string>

#include "meshwave/client/transport.h"
#include "meshwave/client/url.h"
#include "net.h"

namespace meshwave::client {

// A network failure as kIoError (retryable), naming the timeout when it
// was one.
Status NetError(const std::string& what, const beast::error_code& ec,
                std::chrono::milliseconds timeout);

// The Host header for `server` (the port only when not the default).
std::string HostHeader(const ServerUrl& server);

// A non-2xx answer as a status: kIoError for 5xx (worth retrying),
// kNotFound for 404, kInvalidArgument otherwise; the message carries the
// "error" member of the server's JSON body.
Status StatusFromResponse(const std::string& what, unsigned code,
                          const std::string& reason, const std::string& body);

// Resolves the server and connects `stream` within connect_timeout, with
// TCP_NODELAY. kIoError on failure.
net::awaitable<Status> ConnectTcp(beast::tcp_stream& stream,
                                  const ServerUrl& server,
                                  const TransportOptions& options);

// The client TLS context: peer verification against the system's
// certificates or options.ca_file. kInvalidArgument when they cannot load.
Result<std::unique_ptr<ssl::context>> MakeTlsContext(
    const TransportOptions& options);

// ConnectTcp, then the TLS handshake checking the certificate and that it
// names the host (SNI for names). A certificate that does not verify or a
// handshake that cannot succeed is kInvalidArgument (final), the rest
// kIoError.
net::awaitable<Status> ConnectTls(beast::ssl_stream<beast::tcp_stream>& stream,
                                  const ServerUrl& server,
                                  const TransportOptions& options);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_SERVER_CONNECTION_H_
