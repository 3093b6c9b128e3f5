#include "client_options.h"

#include <algorithm>
#include <cmath>

#include "cli_util.h"
#include "meshwave/client/budget.h"

namespace meshwave::cli {
namespace {

Result<std::chrono::milliseconds> Millis(const std::string& text) {
  MW_ASSIGN_OR_RETURN(double seconds, client::ParseDuration(text));
  return std::chrono::milliseconds(
      static_cast<int64_t>(std::ceil(seconds * 1000)));
}

}  // namespace

void AddClientOptions(CLI::App* cmd, ClientArgs& args) {
  cmd->add_option("--connect-timeout", args.connect_timeout,
                  "Time to connect (and finish the TLS handshake), e.g. 5s")
      ->capture_default_str();
  cmd->add_option("--timeout", args.timeout,
                  "Time any single read or write may take")
      ->capture_default_str();
  cmd->add_option(
         "--retries", args.retries,
         "Retries of a request that fails without progress (backoff doubles)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  cmd->add_option("--retry-delay", args.retry_delay,
                  "Wait before the first retry")
      ->capture_default_str();
  cmd->add_option(
      "--ca-file", args.ca_file,
      "PEM certificates to trust for https and wss (default: the system's)");
  cmd->add_option("--pace", args.pace,
                  "WebSocket only: have the server send at this rate (e.g. "
                  "2Mbit, 500kbit, 1MB/s)");
}

Status ApplyClientOptions(const ClientArgs& args,
                          client::TransportOptions& transport,
                          client::RetryPolicy& retry) {
  MW_ASSIGN_OR_RETURN(transport.connect_timeout, Millis(args.connect_timeout));
  MW_ASSIGN_OR_RETURN(transport.read_timeout, Millis(args.timeout));
  MW_ASSIGN_OR_RETURN(retry.initial_delay, Millis(args.retry_delay));
  transport.ca_file = args.ca_file;
  if (!args.pace.empty()) {
    MW_ASSIGN_OR_RETURN(double bits, client::ParseRate(args.pace));
    transport.pace_bytes_per_second =
        std::max<uint64_t>(1, static_cast<uint64_t>(bits / 8));
  }
  retry.max_attempts = args.retries + 1;
  return Status::Ok();
}

void AddDecodeLimitOptions(CLI::App* cmd, DecodeLimitArgs& args) {
  cmd->add_option("--max-header", args.max_header,
                  "Refuse a stream whose header (base mesh and packet index) "
                  "is larger, before reading it (e.g. 16MiB)")
      ->capture_default_str();
  cmd->add_option("--max-faces", args.max_faces,
                  "Refuse a mesh with more faces at its finest level, before "
                  "allocating it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

Status ApplyDecodeLimitOptions(const DecodeLimitArgs& args,
                               client::SessionOptions& session) {
  MW_ASSIGN_OR_RETURN(session.max_header_bytes, ParseByteSize(args.max_header));
  session.decoder.max_faces = args.max_faces;
  return Status::Ok();
}

}  // namespace meshwave::cli
