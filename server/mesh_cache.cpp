#include "mesh_cache.h"

namespace meshwave::server {

Result<std::shared_ptr<const ServedMesh>> MeshCache::Get(const std::string& id) {
  {
    std::lock_guard lock(mutex_);
    auto it = index_.find(id);
    if (it != index_.end()) {
      lru_.splice(lru_.begin(), lru_, it->second);
      return it->second->second;
    }
  }
  // Loading happens outside the lock: two threads may load the same mesh
  // at once, which only wastes a little work.
  MW_ASSIGN_OR_RETURN(auto entry, catalog_.Find(id));
  if (!entry) return std::shared_ptr<const ServedMesh>();
  auto loaded = ServedMesh::Load(*entry, catalog_.ContainerPath(*entry));
  if (!loaded.ok()) {
    // The row may have got another container between the read and the
    // load (a re-encode), and the one it named been removed since: the
    // row as it is now decides.
    MW_ASSIGN_OR_RETURN(auto again, catalog_.Find(id));
    if (!again) return std::shared_ptr<const ServedMesh>();
    if (again->sha256 == entry->sha256) return loaded.status();
    loaded = ServedMesh::Load(*again, catalog_.ContainerPath(*again));
    if (!loaded.ok()) return loaded.status();
  }
  auto mesh = std::move(*loaded);
  std::lock_guard lock(mutex_);
  auto it = index_.find(id);
  if (it != index_.end()) return it->second->second;
  lru_.emplace_front(id, mesh);
  index_[id] = lru_.begin();
  while (lru_.size() > capacity_) {
    lru_.back().second->Retire();
    index_.erase(lru_.back().first);
    lru_.pop_back();
  }
  return mesh;
}

void MeshCache::Evict(const std::string& id) {
  std::lock_guard lock(mutex_);
  auto it = index_.find(id);
  if (it == index_.end()) return;
  it->second->second->Retire();
  lru_.erase(it->second);
  index_.erase(it);
}

bool MeshCache::EvictIf(const std::string& id, const std::string& sha256) {
  std::lock_guard lock(mutex_);
  auto it = index_.find(id);
  if (it == index_.end() || it->second->second->entry().sha256 != sha256) return false;
  it->second->second->Retire();
  lru_.erase(it->second);
  index_.erase(it);
  return true;
}

std::vector<std::pair<std::string, std::string>> MeshCache::Snapshot() const {
  std::lock_guard lock(mutex_);
  std::vector<std::pair<std::string, std::string>> out;
  out.reserve(lru_.size());
  for (const auto& [id, mesh] : lru_) out.emplace_back(id, mesh->entry().sha256);
  return out;
}

size_t MeshCache::size() const {
  std::lock_guard lock(mutex_);
  return lru_.size();
}

}  // namespace meshwave::server
