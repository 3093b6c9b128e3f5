// The catalog: the list of meshes a server offers, next to their
// content-addressed containers in STORE/containers/ and the originals they
// were made from in STORE/originals/ (original_store.h). Two backends share
// this interface: SQLite in a local directory (sqlite_catalog.h, the
// embedded default) and PostgreSQL (postgres_catalog.h) for several
// replicas sharing one catalog and one container store. A row is only
// inserted after its container file is durable, and removed before the
// file is, so an entry is never visible without its file (see ingest.h).
// Implementations are thread-safe; other processes (the ingest command,
// other replicas) may use the same catalog at the same time.
#ifndef MESHWAVE_SERVER_CATALOG_H_
#define MESHWAVE_SERVER_CATALOG_H_

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "meshwave/status.h"
#include "original_store.h"

namespace meshwave::server {

// The columns of a catalog row in CatalogEntry's order, as the `meshes`
// table of both backends names them (their SELECTs and INSERTs list these).
inline constexpr char kCatalogColumns[] =
    "id, name, source, vertices, faces, levels, packets, bytes, container, sha256, created, "
    "format_version, original, settings";

struct CatalogEntry {
  std::string id;  // IsValidMeshId
  std::string name;
  std::string source;  // file name the mesh came from
  uint64_t vertices = 0;
  uint64_t faces = 0;
  uint32_t levels = 0;
  uint32_t packets = 0;
  uint64_t bytes = 0;  // container size
  std::string container;  // path relative to the store directory
  std::string sha256;     // of the container
  int64_t created_unix = 0;
  // The container's stream format version; 0 in rows written before the
  // catalog recorded it (reencode reads it from the container then).
  uint32_t format_version = 0;
  // Original::digest of what the container was made from; empty when none
  // was kept (rows from before originals were kept, or ingested as a
  // ready container): such a mesh cannot be re-encoded.
  std::string original;
  // FormatEncodeSettings of the choices it was encoded with; empty with no
  // original.
  std::string settings;
};

// Held while a container is written and its row inserted, and while
// orphans are removed: every process sharing the store excludes the others.
class IngestGuard {
 public:
  virtual ~IngestGuard() = default;
};

class Catalog {
 public:
  // True for "postgres://..." and "postgresql://..." (PostgreSQL URIs).
  static bool IsPostgresUri(const std::string& location);

  // Opens the catalog `location` names, creating what is missing:
  // - a directory: SQLite (DIR/catalog.db) with containers in
  //   DIR/containers/; `store` must be empty;
  // - a postgres:// URI: PostgreSQL, schema migrated to the newest version
  //   at open; containers in `store`/containers/ (`store` required, shared
  //   by every replica).
  static Result<std::unique_ptr<Catalog>> Open(const std::string& location,
                                               const std::filesystem::path& store = {});

  virtual ~Catalog() = default;
  Catalog(const Catalog&) = delete;
  Catalog& operator=(const Catalog&) = delete;

  // The directory entries' container paths are relative to.
  const std::filesystem::path& store_dir() const { return store_dir_; }
  std::filesystem::path containers_dir() const { return store_dir_ / "containers"; }
  // Absolute path of an entry's container.
  std::filesystem::path ContainerPath(const CatalogEntry& entry) const {
    return store_dir_ / entry.container;
  }
  // Backend and location for logs (never a password).
  virtual std::string Describe() const = 0;

  // Blocks until this process holds the store's ingest lock.
  virtual Result<std::unique_ptr<IngestGuard>> LockIngest() = 0;

  // Inserts in one transaction, with `original` (its rows, when the
  // catalog has none for its digest yet; null: none; its digest must be
  // entry.original). kInvalidArgument when the id exists.
  virtual Status Insert(const CatalogEntry& entry, const Original* original) = 0;
  Status Insert(const CatalogEntry& entry) { return Insert(entry, nullptr); }
  // The entry, or nullopt. `id` must be valid (checked: kInvalidArgument).
  virtual Result<std::optional<CatalogEntry>> Find(const std::string& id) = 0;
  // Entries by creation time then id.
  virtual Result<std::vector<CatalogEntry>> List(uint64_t limit, uint64_t offset) = 0;
  virtual Result<uint64_t> Count() = 0;
  // Deletes the row, and its original's rows when no other mesh uses it;
  // true when it existed. `id` must be valid.
  virtual Result<bool> Remove(const std::string& id) = 0;
  // Container paths (relative) of every row and of the retired containers
  // still kept (ReplaceContainer): what the store must keep.
  virtual Result<std::vector<std::string>> ContainerPaths() = 0;

  // The original with this digest, or nullopt.
  virtual Result<std::optional<Original>> FindOriginal(const std::string& digest) = 0;
  // The digests (sha256) of every file an original of the catalog lists:
  // the blobs of STORE/originals/ to keep.
  virtual Result<std::vector<std::string>> OriginalBlobs() = 0;

  // Swaps the container of mesh `id` in one transaction: when its row still
  // names the container `old_sha256`, its container, sha256, statistics,
  // format version and settings become those of `now` (its id, name,
  // source, original and creation time are kept), and the old container
  // is recorded as retired at `retired_unix`, kept on disk for the readers
  // that may still open it (other replicas) until ExpireRetired. False,
  // changing nothing, when the row is gone or names another container.
  virtual Result<bool> ReplaceContainer(const std::string& id, const std::string& old_sha256,
                                        const CatalogEntry& now, int64_t retired_unix) = 0;
  // Forgets the retired containers retired before `before_unix` that no
  // row names (again), and returns their paths for the caller to remove.
  virtual Result<std::vector<std::string>> ExpireRetired(int64_t before_unix) = 0;

  // A number that changes whenever a row is inserted, removed or gets
  // another container (by any process): servers poll it to drop what
  // they keep of meshes that changed.
  virtual Result<int64_t> Generation() = 0;

 protected:
  explicit Catalog(std::filesystem::path store_dir) : store_dir_(std::move(store_dir)) {}

 private:
  const std::filesystem::path store_dir_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_CATALOG_H_
