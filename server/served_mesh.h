// A catalog entry ready to serve: its container memory-mapped, the header
// parsed and validated once, the packet orders for every level limit and
// the quality order's rate-distortion table computed once. Immutable and
// shared between requests.
#ifndef MESHWAVE_SERVER_SERVED_MESH_H_
#define MESHWAVE_SERVER_SERVED_MESH_H_

#include <atomic>
#include <mutex>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "catalog.h"
#include "mapped_file.h"
#include "meshwave/progression.h"
#include "meshwave/screen_errors.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "unit_table.h"

namespace meshwave::server {

struct RdTablePoint {
  uint32_t packets = 0;
  uint64_t bytes = 0;  // container size
  double psnr_db = 0;
};

class ServedMesh {
 public:
  // Maps and checks the container of `entry` (SHA-256 against the entry's,
  // ParseContainer, ValidateStreamHeader, all packets present): a corrupt
  // file is an error, not a crash and not garbage sent to clients.
  static Result<std::shared_ptr<const ServedMesh>> Load(CatalogEntry entry,
                                                        const std::filesystem::path& file);

  const CatalogEntry& entry() const { return entry_; }
  const std::shared_ptr<const MappedFile>& map() const { return map_; }
  // The StreamHeader with `present` cleared: the same for every truncation.
  const StreamHeader& header() const { return header_; }
  const std::string& header_bytes() const { return header_.bytes_without_present; }
  uint32_t levels() const { return header_.transform.levels; }
  // kInvalidArgument, naming the mesh, for a level limit above its levels.
  Status CheckLevelLimit(int max_level) const;
  size_t packet_count() const { return payloads_.size(); }
  // Payload of packet `id` (< packet_count()), a view into the map.
  std::string_view payload(uint32_t id) const { return payloads_[id]; }
  uint64_t payload_bytes() const { return payload_bytes_; }
  // PacketOrder(header, p, max_level); max_level in [-1, levels()].
  const std::vector<uint32_t>& Order(Progression p, int max_level) const;
  const std::vector<RdTablePoint>& rd_table() const { return rd_table_; }
  // The precincts and units region requests need, built on the first call
  // (thread-safe; tens of milliseconds for a large mesh) and kept.
  Result<const UnitTable*> units() const;
  // What views with a screen-space error judge units by
  // (meshwave/screen_errors.h), measured on the first call (thread-safe; the
  // stream decoded once per bitplane, a few hundred milliseconds for a large
  // mesh) and kept.
  Result<const StreamScreenErrors*> screen_errors() const;

  // Set once the mesh leaves the MeshCache (deleted, or evicted as least
  // recently used): responses planned from it are no longer served from
  // the ResponseCache, even while a write in flight keeps it alive.
  void Retire() const { retired_.store(true, std::memory_order_release); }
  bool retired() const { return retired_.load(std::memory_order_acquire); }

 private:
  ServedMesh() = default;
  CatalogEntry entry_;
  std::shared_ptr<const MappedFile> map_;
  StreamHeader header_;
  std::vector<std::string_view> payloads_;
  uint64_t payload_bytes_ = 0;
  // orders_[3 * (max_level + 1) + progression]
  std::vector<std::vector<uint32_t>> orders_;
  std::vector<RdTablePoint> rd_table_;
  mutable std::atomic<bool> retired_{false};
  mutable std::once_flag units_once_;
  mutable std::unique_ptr<const UnitTable> units_;
  mutable Status units_status_;
  mutable std::once_flag screen_errors_once_;
  mutable std::unique_ptr<const StreamScreenErrors> screen_errors_;
  mutable Status screen_errors_status_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SERVED_MESH_H_
