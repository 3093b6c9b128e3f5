// The embedded catalog backend: an SQLite database (WAL mode) in
// DIR/catalog.db, containers in DIR/containers/, and DIR/ingest.lock as
// the ingest lock (flock). One connection behind a mutex.
#ifndef MESHWAVE_SERVER_SQLITE_CATALOG_H_
#define MESHWAVE_SERVER_SQLITE_CATALOG_H_

#include <sqlite3.h>

#include <functional>
#include <mutex>

#include "catalog.h"
#include "migration.h"

namespace meshwave::server {

class SqliteCatalog final : public Catalog {
 public:
  // Opens (creating when missing or empty) the catalog in `dir`: the
  // directory, DIR/containers/ and DIR/catalog.db in WAL mode.
  static Result<std::unique_ptr<SqliteCatalog>> Open(const std::filesystem::path& dir);
  ~SqliteCatalog() override;

  std::string Describe() const override { return "sqlite " + store_dir().string(); }
  Result<std::unique_ptr<IngestGuard>> LockIngest() override;
  using Catalog::Insert;
  Status Insert(const CatalogEntry& entry, const Original* original) override;
  Result<std::optional<CatalogEntry>> Find(const std::string& id) override;
  Result<std::vector<CatalogEntry>> List(uint64_t limit, uint64_t offset) override;
  Result<uint64_t> Count() override;
  Result<bool> Remove(const std::string& id) override;
  Result<std::vector<std::string>> ContainerPaths() override;
  Result<std::optional<Original>> FindOriginal(const std::string& digest) override;
  Result<std::vector<std::string>> OriginalBlobs() override;
  Result<bool> ReplaceContainer(const std::string& id, const std::string& old_sha256,
                                const CatalogEntry& now, int64_t retired_unix) override;
  Result<std::vector<std::string>> ExpireRetired(int64_t before_unix) override;
  Result<int64_t> Generation() override;
  // "wal" once open.
  Result<std::string> JournalMode();

 private:
  SqliteCatalog(std::filesystem::path dir, sqlite3* db) : Catalog(std::move(dir)), db_(db) {}
  Status Exec(const char* sql);
  // Runs `body` between BEGIN IMMEDIATE and COMMIT (ROLLBACK when it or
  // the commit fails). The caller holds mutex_.
  Status InTransaction(const std::function<Status()>& body);
  Status InsertOriginal(const Original& original, int64_t created);
  Status BumpGeneration();
  Status Migrate(const std::vector<Migration>& migrations);
  Result<std::vector<std::string>> Strings(const char* sql, const std::string& what);
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
  int failed_code_ = SQLITE_OK;  // of the last transaction that failed
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SQLITE_CATALOG_H_
