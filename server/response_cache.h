// Planned responses of the mesh endpoints (packets, streams, headers,
// containers and their ranges), kept so that a repeated GET or HEAD skips
// routing, the mesh lookup, the stream plan, the ETag and the head's
// serialisation: the session writes the cached head and payload slices in
// one gathered write. Bounded in bytes, least recently used evicted first.
// An entry holds its mesh weakly: it is not served once the mesh has left
// the MeshCache (ServedMesh::retired, set on DELETE and on eviction) or
// been freed, so it never sends bytes of a deleted mesh and never keeps a
// memory map open. Thread-safe.
#ifndef MESHWAVE_SERVER_RESPONSE_CACHE_H_
#define MESHWAVE_SERVER_RESPONSE_CACHE_H_

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "net.h"
#include "served_mesh.h"
#include "slices_body.h"

namespace meshwave::server {

// One response ready to write: the head for HTTP/1.1 keep-alive, the
// owned body prefix and the payload slices (adjacent slices merged).
struct CachedResponse {
  unsigned status = 200;
  // "HTTP/1.1 <status> <reason>\r\n" + fields (AppendFields) + "\r\n".
  std::string head;
  size_t fields_begin = 0, fields_end = 0;  // the fields within `head`
  std::string owned;
  std::vector<net::const_buffer> slices;  // into the mesh's memory map
  uint64_t body_bytes = 0;
  std::weak_ptr<const ServedMesh> mesh;

  std::string_view fields() const {
    return std::string_view(head).substr(fields_begin, fields_end - fields_begin);
  }
  // What the entry counts against the cache's bound (its key aside).
  uint64_t charge() const;
};

// The cacheable form of a successful mesh response (body().mesh set);
// consumes the owned prefix.
std::shared_ptr<const CachedResponse> PlanResponse(Response&& response);

class ResponseCache {
 public:
  // `capacity_bytes` 0: nothing is kept.
  explicit ResponseCache(uint64_t capacity_bytes) : capacity_(capacity_bytes) {}

  bool enabled() const { return capacity_ > 0; }

  struct Hit {
    std::shared_ptr<const CachedResponse> response;  // null: a miss
    std::shared_ptr<const ServedMesh> mesh;          // keeps the slices' bytes
  };
  // The entry for `key` while its mesh is alive and not retired (an entry
  // whose mesh is gone is dropped).
  Hit Get(std::string_view key);
  // Keeps `response` under `key` (replacing one there), evicting the least
  // recently used entries past the bound; nothing when the response alone
  // exceeds it or its mesh is gone or retired.
  void Put(std::string_view key, std::shared_ptr<const CachedResponse> response);
  // Drops the entries whose mesh is gone or retired (after a DELETE).
  void EraseRetired();

  uint64_t bytes() const;
  size_t size() const;
  uint64_t hits() const;
  uint64_t misses() const;

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const CachedResponse> response;
    uint64_t charge = 0;
  };
  using Lru = std::list<Entry>;  // most recent first
  void EraseLocked(Lru::iterator it);

  const uint64_t capacity_;
  mutable std::mutex mutex_;
  Lru lru_;
  // Keys are views of the entries' own strings (list nodes do not move).
  std::unordered_map<std::string_view, Lru::iterator> index_;
  uint64_t bytes_ = 0;
  uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_RESPONSE_CACHE_H_
