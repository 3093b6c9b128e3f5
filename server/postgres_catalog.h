// The shared catalog backend: the meshes table in PostgreSQL (schema from
// postgres_migrations.h) and containers in STORE/containers/ on storage
// every replica mounts. The ingest lock is a PostgreSQL advisory lock, so
// it holds across machines whatever the shared filesystem's locking.
// One connection behind a mutex, re-established when it is lost.
#ifndef MESHWAVE_SERVER_POSTGRES_CATALOG_H_
#define MESHWAVE_SERVER_POSTGRES_CATALOG_H_

#include <functional>
#include <mutex>

#include "catalog.h"
#include "postgres_connection.h"

namespace meshwave::server {

class PostgresCatalog final : public Catalog {
 public:
  // Connects to `uri`, migrates the schema, creates `store`/containers/.
  static Result<std::unique_ptr<PostgresCatalog>> Open(const std::string& uri,
                                                       const std::filesystem::path& store);

  std::string Describe() const override;
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

 private:
  PostgresCatalog(std::string uri, std::filesystem::path store,
                  std::unique_ptr<PostgresConnection> conn)
      : Catalog(std::move(store)), uri_(std::move(uri)), conn_(std::move(conn)) {}
  // Runs `query` under the mutex on a live connection. A read-only query
  // that failed because the connection was lost (database restart,
  // failover) is retried once on a new connection.
  Result<PgResult> Run(const std::string& sql, const std::vector<std::string>& params,
                       bool read_only, PgError* error = nullptr);
  // Runs `body` on the connection between BEGIN and COMMIT (ROLLBACK when
  // it or the commit fails), under the mutex.
  Status InTransaction(const std::function<Status(PostgresConnection&)>& body);
  Result<std::vector<std::string>> Strings(const std::string& sql);

  const std::string uri_;
  std::unique_ptr<PostgresConnection> conn_;
  std::mutex mutex_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_POSTGRES_CATALOG_H_
