// The served meshes kept open: at most `capacity` memory maps, least
// recently used evicted first. Responses keep their ServedMesh alive by
// shared_ptr, so eviction and deletion never pull bytes from under a write.
#ifndef MESHWAVE_SERVER_MESH_CACHE_H_
#define MESHWAVE_SERVER_MESH_CACHE_H_

#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "catalog.h"
#include "served_mesh.h"

namespace meshwave::server {

class MeshCache {
 public:
  MeshCache(Catalog& catalog, size_t capacity)
      : catalog_(catalog), capacity_(capacity == 0 ? 1 : capacity) {}

  // The mesh `id` (must be valid), or null when the catalog has no such
  // entry; an error when its container cannot be loaded.
  Result<std::shared_ptr<const ServedMesh>> Get(const std::string& id);
  // Forgets `id` (after a DELETE).
  void Evict(const std::string& id);
  // Forgets `id` if it is open with the container `sha256` (not if it was
  // loaded again since); true when it was.
  bool EvictIf(const std::string& id, const std::string& sha256);
  // The open meshes: id and container SHA-256.
  std::vector<std::pair<std::string, std::string>> Snapshot() const;
  size_t size() const;

 private:
  using Lru = std::list<std::pair<std::string, std::shared_ptr<const ServedMesh>>>;
  Catalog& catalog_;
  const size_t capacity_;
  mutable std::mutex mutex_;
  Lru lru_;  // most recent first
  std::unordered_map<std::string, Lru::iterator> index_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MESH_CACHE_H_
