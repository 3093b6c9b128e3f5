#include "postgres_catalog.h"

#include <algorithm>
#include <charconv>
#include <climits>

#include "meshwave/mesh_id.h"
#include "postgres_migrations.h"

namespace meshwave::server {
namespace {

// pg_advisory_lock key of the ingest lock (any constant every replica
// shares; postgres_migrations.cpp uses the next one).
constexpr char kIngestLockKey[] = "4270537001";

template <class T>
T Number(const std::string& text) {
  T v{};
  std::from_chars(text.data(), text.data() + text.size(), v);
  return v;
}

CatalogEntry ReadRow(const PgResult& r, int row) {
  CatalogEntry e;
  e.id = r.Text(row, 0);
  e.name = r.Text(row, 1);
  e.source = r.Text(row, 2);
  e.vertices = Number<uint64_t>(r.Text(row, 3));
  e.faces = Number<uint64_t>(r.Text(row, 4));
  e.levels = Number<uint32_t>(r.Text(row, 5));
  e.packets = Number<uint32_t>(r.Text(row, 6));
  e.bytes = Number<uint64_t>(r.Text(row, 7));
  e.container = r.Text(row, 8);
  e.sha256 = r.Text(row, 9);
  e.created_unix = Number<int64_t>(r.Text(row, 10));
  return e;
}

// A session-level advisory lock on a connection of its own: released when
// the guard closes that connection, or by the server when the process dies.
class AdvisoryLockGuard final : public IngestGuard {
 public:
  explicit AdvisoryLockGuard(std::unique_ptr<PostgresConnection> conn) : conn_(std::move(conn)) {}

 private:
  std::unique_ptr<PostgresConnection> conn_;
};

}  // namespace

Result<std::unique_ptr<PostgresCatalog>> PostgresCatalog::Open(
    const std::string& uri, const std::filesystem::path& store) {
  std::error_code ec;
  std::filesystem::create_directories(store / "containers", ec);
  if (ec) {
    return IoError("catalog: cannot create " + (store / "containers").string() + ": " +
                   ec.message());
  }
  MW_ASSIGN_OR_RETURN(auto conn, PostgresConnection::Connect(uri));
  MW_RETURN_IF_ERROR(MigrateSchema(*conn, PostgresMigrations()));
  return std::unique_ptr<PostgresCatalog>(
      new PostgresCatalog(uri, std::filesystem::absolute(store), std::move(conn)));
}

std::string PostgresCatalog::Describe() const {
  return "postgres " + DescribePostgresUri(uri_) + ", store " + store_dir().string();
}

Result<PgResult> PostgresCatalog::Run(const std::string& sql,
                                      const std::vector<std::string>& params, bool read_only,
                                      PgError* error) {
  std::lock_guard lock(mutex_);
  if (conn_->broken()) MW_RETURN_IF_ERROR(conn_->Reset());
  auto result = conn_->Exec(sql, params, error);
  if (!result.ok() && read_only && conn_->broken()) {
    MW_RETURN_IF_ERROR(conn_->Reset());
    return conn_->Exec(sql, params, error);
  }
  return result;
}

Result<std::unique_ptr<IngestGuard>> PostgresCatalog::LockIngest() {
  MW_ASSIGN_OR_RETURN(auto conn, PostgresConnection::Connect(uri_));
  MW_RETURN_IF_ERROR(conn->Exec("SELECT pg_advisory_lock($1::bigint)", {kIngestLockKey})
                         .status()
                         .WithContext("catalog: ingest lock"));
  return std::unique_ptr<IngestGuard>(new AdvisoryLockGuard(std::move(conn)));
}

Status PostgresCatalog::Insert(const CatalogEntry& e) {
  if (!IsValidMeshId(e.id)) return InvalidArgument("catalog: invalid id '" + e.id + "'");
  PgError error;
  // One statement: its own transaction, committed (synchronous_commit on
  // the server decides durability) before this returns.
  auto r = Run(std::string("INSERT INTO meshes (") + kCatalogColumns +
                   ") VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11)",
               {e.id, e.name, e.source, std::to_string(e.vertices), std::to_string(e.faces),
                std::to_string(e.levels), std::to_string(e.packets), std::to_string(e.bytes),
                e.container, e.sha256, std::to_string(e.created_unix)},
               /*read_only=*/false, &error);
  if (!r.ok()) {
    if (error.sqlstate == "23505") return InvalidArgument("catalog: id " + e.id + " exists");
    return r.status();
  }
  return Status::Ok();
}

Result<std::optional<CatalogEntry>> PostgresCatalog::Find(const std::string& id) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  MW_ASSIGN_OR_RETURN(PgResult r, Run(std::string("SELECT ") + kCatalogColumns +
                                          " FROM meshes WHERE id = $1",
                                      {id}, /*read_only=*/true));
  if (r.rows() == 0) return std::optional<CatalogEntry>();
  return std::optional<CatalogEntry>(ReadRow(r, 0));
}

Result<std::vector<CatalogEntry>> PostgresCatalog::List(uint64_t limit, uint64_t offset) {
  // bigint is signed 64-bit; larger values mean "all" anyway.
  constexpr uint64_t kMax = static_cast<uint64_t>(INT64_MAX);
  MW_ASSIGN_OR_RETURN(
      PgResult r, Run(std::string("SELECT ") + kCatalogColumns +
                          " FROM meshes ORDER BY created, id LIMIT $1 OFFSET $2",
                      {std::to_string(std::min(limit, kMax)), std::to_string(std::min(offset, kMax))},
                      /*read_only=*/true));
  std::vector<CatalogEntry> out;
  out.reserve(static_cast<size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) out.push_back(ReadRow(r, i));
  return out;
}

Result<uint64_t> PostgresCatalog::Count() {
  MW_ASSIGN_OR_RETURN(PgResult r, Run("SELECT count(*) FROM meshes", {}, /*read_only=*/true));
  return Number<uint64_t>(r.Text(0, 0));
}

Result<bool> PostgresCatalog::Remove(const std::string& id) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  MW_ASSIGN_OR_RETURN(PgResult r,
                      Run("DELETE FROM meshes WHERE id = $1", {id}, /*read_only=*/false));
  return r.affected() > 0;
}

Result<std::vector<std::string>> PostgresCatalog::ContainerPaths() {
  MW_ASSIGN_OR_RETURN(PgResult r, Run("SELECT container FROM meshes", {}, /*read_only=*/true));
  std::vector<std::string> out;
  out.reserve(static_cast<size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) out.push_back(r.Text(i, 0));
  return out;
}

}  // namespace meshwave::server
