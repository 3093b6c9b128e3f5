// Re-encoding the catalog from its originals: every mesh whose container is
// of an older stream format version, or was made with other settings than
// asked, gets a new container made from its original, swapped in
// atomically (Catalog::ReplaceContainer). The old container is served
// until the swap and kept on disk a while after it (retired), so no reader
// ever finds a mesh without a container. Each mesh is independent: an
// interrupted run (even kill -9) loses nothing, and running it again
// continues with the meshes not yet done.
#ifndef MESHWAVE_SERVER_REENCODE_H_
#define MESHWAVE_SERVER_REENCODE_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "bulk_ingest.h"
#include "catalog.h"
#include "encode_settings.h"
#include "meshwave/status.h"

namespace meshwave::server {

// Settings to change: each one given replaces the mesh's recorded value.
struct SettingsChange {
  std::optional<double> fidelity_db;
  std::optional<double> max_vertex_ratio;
  std::optional<bool> force_remesh;
  std::optional<uint32_t> precinct_coefficients;
  std::optional<uint32_t> split_bytes_per_precinct;

  EncodeChoices ApplyTo(EncodeChoices choices) const;
};

struct ReencodeOptions {
  SettingsChange change;
  Shard shard;           // only the meshes whose id is InShard (bulk_ingest.h)
  bool dry_run = false;  // say what would be done, change nothing
  int threads = 0;       // per mesh; 0: the machine's cores
};

enum class ReencodeAction {
  kCurrent,       // already of this format version and settings
  kReencoded,     // a new container swapped in
  kNoOriginal,    // nothing to make it from
  kWouldReencode,  // dry run
  kChanged,       // deleted or swapped by another process meanwhile: left alone
  kFailed,
};

struct ReencodeStep {
  CatalogEntry before;
  CatalogEntry after;  // kReencoded: the row as it is now
  ReencodeAction action = ReencodeAction::kCurrent;
  std::string why;     // what is out of date, or what went wrong
  double seconds = 0;
};

struct ReencodeReport {
  size_t meshes = 0, current = 0, reencoded = 0, no_original = 0, changed = 0, failed = 0;
};

// Re-encodes what is out of date, one mesh at a time; `progress` is told
// about each mesh as it is done (position, count, step).
Result<ReencodeReport> ReencodeCatalog(
    Catalog& catalog, const ReencodeOptions& options,
    const std::function<void(size_t, size_t, const ReencodeStep&)>& progress);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_REENCODE_H_
