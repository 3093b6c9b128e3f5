// Keeps a server's open meshes in step with a catalog other processes
// change: `meshwave-server reencode` swapping a container in, an ingest
// job, another replica's upload or delete. It polls the catalog's
// generation (Catalog::Generation) on a thread of its own, and when it has
// moved, drops each open mesh whose row is gone or names another container;
// the next request loads the row as it is now. Until then the old
// container is served whole (it stays on disk a while: ingest.h,
// kDefaultRetiredSeconds).
#ifndef MESHWAVE_SERVER_CATALOG_WATCHER_H_
#define MESHWAVE_SERVER_CATALOG_WATCHER_H_

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "catalog.h"
#include "mesh_cache.h"
#include "response_cache.h"

namespace meshwave::server {

class CatalogWatcher {
 public:
  CatalogWatcher(Catalog& catalog, MeshCache& meshes, ResponseCache& responses,
                 std::chrono::milliseconds period);
  ~CatalogWatcher();  // stops the thread
  CatalogWatcher(const CatalogWatcher&) = delete;
  CatalogWatcher& operator=(const CatalogWatcher&) = delete;

  // One poll, on the caller's thread: how many open meshes were dropped.
  size_t CheckNow();

 private:
  void Run();

  Catalog& catalog_;
  MeshCache& meshes_;
  ResponseCache& responses_;
  const std::chrono::milliseconds period_;
  int64_t seen_generation_ = -1;
  std::mutex mutex_;  // guards stop_ and serializes CheckNow
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_CATALOG_WATCHER_H_
