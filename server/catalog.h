// The catalog: an SQLite database (WAL mode) of the meshes a server offers,
// next to their content-addressed containers in DIR/containers/. A row is
// only inserted after its container file is durable, and removed before the
// file is, so an entry is never visible without its file (see ingest.h).
// Thread-safe: one connection behind a mutex; other processes (the ingest
// command) may use the same directory at the same time.
#ifndef MESHWAVE_SERVER_CATALOG_H_
#define MESHWAVE_SERVER_CATALOG_H_

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "meshwave/status.h"

namespace meshwave::server {

struct CatalogEntry {
  std::string id;  // IsValidMeshId
  std::string name;
  std::string source;  // file name the mesh came from
  uint64_t vertices = 0;
  uint64_t faces = 0;
  uint32_t levels = 0;
  uint32_t packets = 0;
  uint64_t bytes = 0;  // container size
  std::string container;  // path relative to the catalog directory
  std::string sha256;     // of the container
  int64_t created_unix = 0;
};

class Catalog {
 public:
  // Opens (creating when missing or empty) the catalog in `dir`: the
  // directory, DIR/containers/ and DIR/catalog.db in WAL mode.
  static Result<std::unique_ptr<Catalog>> Open(const std::filesystem::path& dir);
  ~Catalog();
  Catalog(const Catalog&) = delete;
  Catalog& operator=(const Catalog&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path containers_dir() const { return dir_ / "containers"; }
  // Absolute path of an entry's container.
  std::filesystem::path ContainerPath(const CatalogEntry& entry) const {
    return dir_ / entry.container;
  }

  // Inserts in one transaction. kInvalidArgument when the id exists.
  Status Insert(const CatalogEntry& entry);
  // The entry, or nullopt. `id` must be valid (checked: kInvalidArgument).
  Result<std::optional<CatalogEntry>> Find(const std::string& id);
  // Entries by creation time then id.
  Result<std::vector<CatalogEntry>> List(uint64_t limit, uint64_t offset);
  Result<uint64_t> Count();
  // Deletes the row; true when it existed.
  Result<bool> Remove(const std::string& id);
  // Container paths (relative) of every row.
  Result<std::vector<std::string>> ContainerPaths();
  // "wal" once open.
  Result<std::string> JournalMode();

 private:
  Catalog(std::filesystem::path dir, sqlite3* db) : dir_(std::move(dir)), db_(db) {}
  Status Exec(const char* sql);

  std::filesystem::path dir_;
  sqlite3* db_;
  std::mutex mutex_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_CATALOG_H_
