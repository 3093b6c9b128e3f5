// Running the HTTP server until SIGINT or SIGTERM.
#ifndef MESHWAVE_SERVER_SERVER_H_
#define MESHWAVE_SERVER_SERVER_H_

#include <filesystem>
#include <string>

#include "meshwave/status.h"
#include "server_config.pb.h"

namespace meshwave::server {

struct ServeOptions {
  std::string catalog;              // directory (SQLite) or postgres:// URI
  std::filesystem::path store;      // container store of a PostgreSQL catalog
  proto::ServerConfig config;      // finished (FinishServerConfig)
  std::filesystem::path port_file;  // empty: none
};

// Opens (or creates) the catalog, removes orphan files, listens, writes the
// bound port to `port_file`, serves with config.threads() io threads, and
// on SIGINT/SIGTERM stops accepting, lets in-flight responses finish (at
// most shutdown_grace_seconds) and returns Ok.
Status RunServer(const ServeOptions& options);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SERVER_H_
