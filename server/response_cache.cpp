#include "response_cache.h"

#include "http_head.h"

namespace meshwave::server {
namespace {

// Bookkeeping per entry besides its strings and slices: the list node, the
// index slot and the shared_ptr control blocks, roughly.
constexpr uint64_t kEntryOverhead = 192;

}  // namespace

uint64_t CachedResponse::charge() const {
  return sizeof(CachedResponse) + head.capacity() + owned.capacity() +
         slices.capacity() * sizeof(net::const_buffer) + kEntryOverhead;
}

std::shared_ptr<const CachedResponse> PlanResponse(Response&& response) {
  auto c = std::make_shared<CachedResponse>();
  c->status = response.result_int();
  c->mesh = response.body().mesh;
  c->body_bytes = response.body().size();
  AppendStatusLine(c->head, 11, c->status);
  c->fields_begin = c->head.size();
  AppendFields(c->head, response, c->body_bytes, false);
  c->fields_end = c->head.size();
  c->head += "\r\n";
  c->head.shrink_to_fit();
  c->owned = std::move(response.body().owned);
  // Packets next to each other in the container go out as one iovec.
  for (const auto& s : response.body().slices) {
    if (!c->slices.empty()) {
      auto& last = c->slices.back();
      if (static_cast<const char*>(last.data()) + last.size() == s.data()) {
        last = net::const_buffer(last.data(), last.size() + s.size());
        continue;
      }
    }
    c->slices.push_back(s);
  }
  c->slices.shrink_to_fit();
  return c;
}

ResponseCache::Hit ResponseCache::Get(std::string_view key) {
  std::lock_guard lock(mutex_);
  auto it = index_.find(key);
  if (it == index_.end()) {
    ++misses_;
    return {};
  }
  const Lru::iterator entry = it->second;
  auto mesh = entry->response->mesh.lock();
  if (!mesh || mesh->retired()) {
    EraseLocked(entry);
    ++misses_;
    return {};
  }
  lru_.splice(lru_.begin(), lru_, entry);
  ++hits_;
  return {entry->response, std::move(mesh)};
}

void ResponseCache::Put(std::string_view key, std::shared_ptr<const CachedResponse> response) {
  if (!enabled() || !response) return;
  const uint64_t charge = response->charge() + 2 * key.size();
  if (charge > capacity_) return;
  std::lock_guard lock(mutex_);
  // Checked under the lock: a DELETE retires the mesh before it erases
  // its entries, so an entry planned just before cannot slip in after.
  auto mesh = response->mesh.lock();
  if (!mesh || mesh->retired()) return;
  if (auto it = index_.find(key); it != index_.end()) EraseLocked(it->second);
  lru_.push_front(Entry{std::string(key), std::move(response), charge});
  index_.emplace(lru_.front().key, lru_.begin());
  bytes_ += charge;
  while (bytes_ > capacity_ && !lru_.empty()) EraseLocked(std::prev(lru_.end()));
}

void ResponseCache::EraseRetired() {
  std::lock_guard lock(mutex_);
  for (auto it = lru_.begin(); it != lru_.end();) {
    const auto next = std::next(it);
    auto mesh = it->response->mesh.lock();
    if (!mesh || mesh->retired()) EraseLocked(it);
    it = next;
  }
}

void ResponseCache::EraseLocked(Lru::iterator it) {
  index_.erase(std::string_view(it->key));
  bytes_ -= it->charge;
  lru_.erase(it);
}

uint64_t ResponseCache::bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

size_t ResponseCache::size() const {
  std::lock_guard lock(mutex_);
  return lru_.size();
}

uint64_t ResponseCache::hits() const {
  std::lock_guard lock(mutex_);
  return hits_;
}

uint64_t ResponseCache::misses() const {
  std::lock_guard lock(mutex_);
  return misses_;
}

}  // namespace meshwave::server
