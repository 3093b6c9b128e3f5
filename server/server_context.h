// What every connection of one server shares: settings, catalog, open
// containers, counters, the ingest worker and the list of live sessions
// (for a graceful shutdown). Owned by RunServer, outlives every session.
#ifndef MESHWAVE_SERVER_SERVER_CONTEXT_H_
#define MESHWAVE_SERVER_SERVER_CONTEXT_H_

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "catalog.h"
#include "mesh_cache.h"
#include "metrics.h"
#include "net.h"
#include "request_rate_limiter.h"
#include "response_cache.h"
#include "server_config.pb.h"

namespace meshwave::server {

// A connection the server can ask to finish its current response and close.
class Closable {
 public:
  virtual ~Closable() = default;
  virtual void Shutdown() = 0;  // thread-safe
};

class ServerContext {
 public:
  ServerContext(proto::ServerConfig config, std::unique_ptr<Catalog> catalog)
      : config_(std::move(config)),
        catalog_(std::move(catalog)),
        cache_(*catalog_, config_.open_containers()),
        rate_limiter_(config_.rate_limit_requests_per_second(), config_.rate_limit_burst()),
        response_cache_(config_.response_cache_bytes()) {}

  const proto::ServerConfig& config() const { return config_; }
  Catalog& catalog() { return *catalog_; }
  MeshCache& cache() { return cache_; }
  Metrics& metrics() { return metrics_; }
  RequestRateLimiter& rate_limiter() { return rate_limiter_; }
  ResponseCache& response_cache() { return response_cache_; }
  // Runs uploads (parse, remesh, encode, write) off the io threads: one at
  // a time, as remeshing already uses both cores.
  net::thread_pool& ingest_pool() { return ingest_pool_; }
  // Where the catalog is, for the upload worker process (upload_worker.h)
  // to open it too; empty: uploads are ingested in this process.
  void set_catalog_location(std::string location, std::filesystem::path store) {
    catalog_location_ = std::move(location);
    store_location_ = std::move(store);
  }
  const std::string& catalog_location() const { return catalog_location_; }
  const std::filesystem::path& store_location() const { return store_location_; }

  bool stopping() const { return stopping_.load(); }
  void Register(const std::shared_ptr<Closable>& session);
  // Sets stopping and asks every live session to close after its response.
  void ShutdownSessions();

 private:
  proto::ServerConfig config_;
  std::unique_ptr<Catalog> catalog_;
  MeshCache cache_;
  Metrics metrics_;
  RequestRateLimiter rate_limiter_;
  ResponseCache response_cache_;
  net::thread_pool ingest_pool_{1};
  std::string catalog_location_;
  std::filesystem::path store_location_;
  std::atomic<bool> stopping_{false};
  std::mutex sessions_mutex_;
  std::vector<std::weak_ptr<Closable>> sessions_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SERVER_CONTEXT_H_
