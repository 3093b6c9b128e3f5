#include "catalog_watcher.h"

#include <spdlog/spdlog.h>

namespace meshwave::server {

CatalogWatcher::CatalogWatcher(Catalog& catalog, MeshCache& meshes, ResponseCache& responses,
                               std::chrono::milliseconds period)
    : catalog_(catalog), meshes_(meshes), responses_(responses), period_(period) {
  thread_ = std::thread([this] { Run(); });
}

CatalogWatcher::~CatalogWatcher() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

size_t CatalogWatcher::CheckNow() {
  auto generation = catalog_.Generation();
  if (!generation.ok()) {
    spdlog::warn("catalog {}: cannot read its generation: {}", catalog_.Describe(),
                 generation.status().ToString());
    return 0;
  }
  if (*generation == seen_generation_) return 0;
  size_t dropped = 0;
  for (const auto& [id, sha256] : meshes_.Snapshot()) {
    auto row = catalog_.Find(id);
    if (!row.ok()) return dropped;  // try again at the next poll
    if (*row && (*row)->sha256 == sha256) continue;
    if (meshes_.EvictIf(id, sha256)) ++dropped;
  }
  if (dropped > 0) {
    responses_.EraseRetired();
    spdlog::info("catalog changed (generation {}): {} open mesh(es) will be loaded again",
                 *generation, dropped);
  }
  seen_generation_ = *generation;
  return dropped;
}

void CatalogWatcher::Run() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, period_, [this] { return stop_; })) {
    CheckNow();
  }
}

}  // namespace meshwave::server
