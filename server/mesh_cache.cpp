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
  const auto path = catalog_.ContainerPath(*entry);
  MW_ASSIGN_OR_RETURN(auto mesh, ServedMesh::Load(std::move(*entry), path));
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

size_t MeshCache::size() const {
  std::lock_guard lock(mutex_);
  return lru_.size();
}

}  // namespace meshwave::server
