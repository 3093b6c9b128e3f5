// The embedded catalog backend: an SQLite database (WAL mode) in
// DIR/catalog.db, containers in DIR/containers/, and DIR/ingest.lock as
// the ingest lock (flock). One connection behind a mutex.
#ifndef MESHWAVE_SERVER_SQLITE_CATALOG_H_
#define MESHWAVE_SERVER_SQLITE_CATALOG_H_

#include <sqlite3.h>

#include <mutex>

#include "catalog.h"

namespace meshwave::server {

class SqliteCatalog final : public Catalog {
 public:
  // Opens (creating when missing or empty) the catalog in `dir`: the
  // directory, DIR/containers/ and DIR/catalog.db in WAL mode.
  static Result<std::unique_ptr<SqliteCatalog>> Open(const std::filesystem::path& dir);
  ~SqliteCatalog() override;

  std::string Describe() const override { return "sqlite " + store_dir().string(); }
  Result<std::unique_ptr<IngestGuard>> LockIngest() override;
  Status Insert(const CatalogEntry& entry) override;
  Result<std::optional<CatalogEntry>> Find(const std::string& id) override;
  Result<std::vector<CatalogEntry>> List(uint64_t limit, uint64_t offset) override;
  Result<uint64_t> Count() override;
  Result<bool> Remove(const std::string& id) override;
  Result<std::vector<std::string>> ContainerPaths() override;
  // "wal" once open.
  Result<std::string> JournalMode();

 private:
  SqliteCatalog(std::filesystem::path dir, sqlite3* db) : Catalog(std::move(dir)), db_(db) {}
  Status Exec(const char* sql);
  // DIR/catalog.reserve, kReserveBytes of written zeros: room that a
  // DELETE on a full disk takes for its WAL frames (SQLite otherwise
  // answers "database or disk is full" to the request that would free
  // space). Recreated, when there is room, after each delete.
  static constexpr size_t kReserveBytes = 128 * 1024;
  std::filesystem::path reserve_path() const;
  void KeepReserve();
  bool ReleaseReserve();  // true when there was one to release

  sqlite3* db_;
  std::mutex mutex_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SQLITE_CATALOG_H_
