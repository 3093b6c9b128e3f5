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

// Every change bumps the generation (catalog.h, Generation).
constexpr char kBumpGeneration[] =
    "UPDATE catalog_generation SET generation = generation + 1";

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
  e.format_version = Number<uint32_t>(r.Text(row, 11));
  e.original = r.Text(row, 12);
  e.settings = r.Text(row, 13);
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

Status PostgresCatalog::InTransaction(const std::function<Status(PostgresConnection&)>& body) {
  std::lock_guard lock(mutex_);
  if (conn_->broken()) MW_RETURN_IF_ERROR(conn_->Reset());
  MW_RETURN_IF_ERROR(conn_->ExecScript("BEGIN"));
  Status s = body(*conn_);
  if (s.ok()) s = conn_->ExecScript("COMMIT");
  if (!s.ok()) (void)conn_->ExecScript("ROLLBACK");
  return s;
}

Status PostgresCatalog::Insert(const CatalogEntry& e, const Original* original) {
  if (!IsValidMeshId(e.id)) return InvalidArgument("catalog: invalid id '" + e.id + "'");
  if (original && original->digest != e.original) {
    return Status(StatusCode::kInternal, "catalog: the original is not the entry's");
  }
  return InTransaction([&](PostgresConnection& conn) -> Status {
    if (original) {
      MW_ASSIGN_OR_RETURN(
          PgResult r,
          conn.Exec("INSERT INTO originals (digest, main, format, bytes, created) "
                    "VALUES ($1, $2, $3, $4, $5) ON CONFLICT (digest) DO NOTHING",
                    {original->digest, original->main, original->format,
                     std::to_string(original->bytes), std::to_string(e.created_unix)}));
      if (r.affected() > 0) {
        for (const OriginalFile& f : original->files) {
          MW_RETURN_IF_ERROR(conn.Exec("INSERT INTO original_files (original, name, sha256, "
                                       "bytes) VALUES ($1, $2, $3, $4)",
                                       {original->digest, f.name, f.sha256,
                                        std::to_string(f.bytes)})
                                 .status());
        }
      }
    }
    PgError error;
    auto r = conn.Exec(std::string("INSERT INTO meshes (") + kCatalogColumns +
                           ") VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14)",
                       {e.id, e.name, e.source, std::to_string(e.vertices),
                        std::to_string(e.faces), std::to_string(e.levels),
                        std::to_string(e.packets), std::to_string(e.bytes), e.container, e.sha256,
                        std::to_string(e.created_unix), std::to_string(e.format_version),
                        e.original, e.settings},
                       &error);
    if (!r.ok()) {
      if (error.sqlstate == "23505") return InvalidArgument("catalog: id " + e.id + " exists");
      return r.status();
    }
    return conn.Exec(kBumpGeneration).status();
  });
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
  bool removed = false;
  if (Status done = InTransaction([&](PostgresConnection& conn) -> Status {
    MW_ASSIGN_OR_RETURN(PgResult r,
                        conn.Exec("DELETE FROM meshes WHERE id = $1 RETURNING original", {id}));
    removed = r.rows() > 0;
    if (!removed) return Status::Ok();
    const std::string original = r.Text(0, 0);
    if (!original.empty()) {
      // The original goes with its last mesh (its blobs: ingest.h); its
      // files by ON DELETE CASCADE.
      MW_RETURN_IF_ERROR(conn.Exec("DELETE FROM originals WHERE digest = $1 AND NOT EXISTS "
                                   "(SELECT 1 FROM meshes WHERE original = $1)",
                                   {original})
                             .status());
    }
    return conn.Exec(kBumpGeneration).status();
  }); !done.ok()) {
    return done;
  }
  return removed;
}

Result<std::vector<std::string>> PostgresCatalog::Strings(const std::string& sql) {
  MW_ASSIGN_OR_RETURN(PgResult r, Run(sql, {}, /*read_only=*/true));
  std::vector<std::string> out;
  out.reserve(static_cast<size_t>(r.rows()));
  for (int i = 0; i < r.rows(); ++i) out.push_back(r.Text(i, 0));
  return out;
}

Result<std::vector<std::string>> PostgresCatalog::ContainerPaths() {
  return Strings("SELECT container FROM meshes UNION SELECT container FROM retired_containers");
}

Result<std::vector<std::string>> PostgresCatalog::OriginalBlobs() {
  return Strings("SELECT DISTINCT sha256 FROM original_files");
}

Result<std::optional<Original>> PostgresCatalog::FindOriginal(const std::string& digest) {
  MW_ASSIGN_OR_RETURN(PgResult r, Run("SELECT main, format, bytes FROM originals WHERE digest = $1",
                                      {digest}, /*read_only=*/true));
  if (r.rows() == 0) return std::optional<Original>();
  Original o;
  o.digest = digest;
  o.main = r.Text(0, 0);
  o.format = r.Text(0, 1);
  o.bytes = Number<uint64_t>(r.Text(0, 2));
  MW_ASSIGN_OR_RETURN(PgResult files,
                      Run("SELECT name, sha256, bytes FROM original_files WHERE original = $1 "
                          "ORDER BY name COLLATE \"C\"",
                          {digest}, /*read_only=*/true));
  for (int i = 0; i < files.rows(); ++i) {
    o.files.push_back({files.Text(i, 0), files.Text(i, 1), Number<uint64_t>(files.Text(i, 2))});
  }
  return std::optional<Original>(std::move(o));
}

Result<bool> PostgresCatalog::ReplaceContainer(const std::string& id,
                                               const std::string& old_sha256,
                                               const CatalogEntry& now, int64_t retired_unix) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  bool replaced = false;
  if (Status done = InTransaction([&](PostgresConnection& conn) -> Status {
    MW_ASSIGN_OR_RETURN(PgResult old, conn.Exec("SELECT container FROM meshes WHERE id = $1 AND "
                                                "sha256 = $2 FOR UPDATE",
                                                {id, old_sha256}));
    if (old.rows() == 0) return Status::Ok();
    const std::string old_container = old.Text(0, 0);
    MW_RETURN_IF_ERROR(
        conn.Exec("UPDATE meshes SET vertices = $1, faces = $2, levels = $3, packets = $4, "
                  "bytes = $5, container = $6, sha256 = $7, format_version = $8, settings = $9 "
                  "WHERE id = $10",
                  {std::to_string(now.vertices), std::to_string(now.faces),
                   std::to_string(now.levels), std::to_string(now.packets),
                   std::to_string(now.bytes), now.container, now.sha256,
                   std::to_string(now.format_version), now.settings, id})
            .status());
    if (old_container != now.container) {
      MW_RETURN_IF_ERROR(conn.Exec("INSERT INTO retired_containers (container, retired) "
                                   "VALUES ($1, $2) ON CONFLICT (container) DO UPDATE SET "
                                   "retired = excluded.retired",
                                   {old_container, std::to_string(retired_unix)})
                             .status());
    }
    replaced = true;
    return conn.Exec(kBumpGeneration).status();
  }); !done.ok()) {
    return done;
  }
  return replaced;
}

Result<std::vector<std::string>> PostgresCatalog::ExpireRetired(int64_t before_unix) {
  std::vector<std::string> out;
  if (Status done = InTransaction([&](PostgresConnection& conn) -> Status {
    // A container a row names again (the same bytes made anew) stays.
    MW_ASSIGN_OR_RETURN(
        PgResult r,
        conn.Exec("DELETE FROM retired_containers r WHERE retired < $1 RETURNING container, "
                  "EXISTS (SELECT 1 FROM meshes m WHERE m.container = r.container)",
                  {std::to_string(before_unix)}));
    for (int i = 0; i < r.rows(); ++i) {
      if (r.Text(i, 1) == "f") out.push_back(r.Text(i, 0));
    }
    return Status::Ok();
  }); !done.ok()) {
    return done;
  }
  return out;
}

Result<int64_t> PostgresCatalog::Generation() {
  MW_ASSIGN_OR_RETURN(PgResult r, Run("SELECT generation FROM catalog_generation", {},
                                      /*read_only=*/true));
  if (r.rows() != 1) return Status(StatusCode::kInternal, "catalog: no generation row");
  return Number<int64_t>(r.Text(0, 0));
}

}  // namespace meshwave::server
