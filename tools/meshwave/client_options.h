// The network options of the commands that talk to a server (fetch,
// refine, catalog): timeouts, retries, trusted certificates.
#ifndef MESHWAVE_TOOLS_CLIENT_OPTIONS_H_
#define MESHWAVE_TOOLS_CLIENT_OPTIONS_H_

#include <string>

#include <CLI/CLI.hpp>

#include "meshwave/client/backoff.h"
#include "meshwave/client/session.h"
#include "meshwave/client/transport.h"
#include "meshwave/stream_limits.h"

namespace meshwave::cli {

struct ClientArgs {
  std::string connect_timeout = "5s";
  std::string timeout = "10s";
  int retries = 5;
  std::string retry_delay = "100ms";
  std::string ca_file;
  std::string pace;  // WebSocket: the rate the server sends at
};

void AddClientOptions(CLI::App* cmd, ClientArgs& args);
Status ApplyClientOptions(const ClientArgs& args,
                          client::TransportOptions& transport,
                          client::RetryPolicy& retry);

// The limits of the commands that decode a server's stream (fetch, refine):
// how big a header and a mesh the client accepts before allocating.
struct DecodeLimitArgs {
  std::string max_header = std::to_string(kMaxHeaderBytes >> 20) + "MiB";
  uint64_t max_faces = uint64_t{1} << 27;
};

void AddDecodeLimitOptions(CLI::App* cmd, DecodeLimitArgs& args);
Status ApplyDecodeLimitOptions(const DecodeLimitArgs& args,
                               client::SessionOptions& session);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_CLIENT_OPTIONS_H_
