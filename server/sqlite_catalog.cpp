#include "sqlite_catalog.h"

#include <fstream>
#include <utility>

#include "ingest_lock.h"
#include "meshwave/mesh_id.h"
#include "migration.h"

namespace meshwave::server {
namespace {

// A prepared statement, finalized on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql) {
    rc_ = sqlite3_prepare_v2(db, sql, -1, &stmt_, nullptr);
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  bool ok() const { return rc_ == SQLITE_OK; }
  sqlite3_stmt* get() { return stmt_; }
  void Bind(int i, const std::string& s) {
    sqlite3_bind_text(stmt_, i, s.data(), static_cast<int>(s.size()), SQLITE_TRANSIENT);
  }
  void Bind(int i, int64_t v) { sqlite3_bind_int64(stmt_, i, v); }
  int Step() { return sqlite3_step(stmt_); }
  std::string Text(int i) {
    const auto* p = sqlite3_column_text(stmt_, i);
    return p ? std::string(reinterpret_cast<const char*>(p)) : std::string();
  }
  int64_t Int(int i) { return sqlite3_column_int64(stmt_, i); }

 private:
  sqlite3_stmt* stmt_ = nullptr;
  int rc_ = SQLITE_ERROR;
};

Status SqlError(sqlite3* db, const std::string& what) {
  return IoError("catalog: " + what + ": " + sqlite3_errmsg(db));
}

CatalogEntry ReadRow(Statement& st) {
  CatalogEntry e;
  e.id = st.Text(0);
  e.name = st.Text(1);
  e.source = st.Text(2);
  e.vertices = static_cast<uint64_t>(st.Int(3));
  e.faces = static_cast<uint64_t>(st.Int(4));
  e.levels = static_cast<uint32_t>(st.Int(5));
  e.packets = static_cast<uint32_t>(st.Int(6));
  e.bytes = static_cast<uint64_t>(st.Int(7));
  e.container = st.Text(8);
  e.sha256 = st.Text(9);
  e.created_unix = st.Int(10);
  e.format_version = static_cast<uint32_t>(st.Int(11));
  e.original = st.Text(12);
  e.settings = st.Text(13);
  return e;
}

}  // namespace

Result<std::unique_ptr<SqliteCatalog>> SqliteCatalog::Open(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir / "containers", ec);
  if (ec) return IoError("catalog: cannot create " + (dir / "containers").string() + ": " + ec.message());
  const std::filesystem::path db_path = dir / "catalog.db";
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(db_path.c_str(), &db,
                                 SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE |
                                     SQLITE_OPEN_FULLMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    Status s = IoError("catalog: cannot open " + db_path.string() + ": " +
                       (db ? sqlite3_errmsg(db) : sqlite3_errstr(rc)));
    sqlite3_close(db);
    return s;
  }
  std::unique_ptr<SqliteCatalog> catalog(new SqliteCatalog(dir, db));
  // Another process (ingest) may hold the write lock for a moment.
  sqlite3_busy_timeout(db, 10000);
  MW_RETURN_IF_ERROR(catalog->Exec("PRAGMA journal_mode=WAL;"));
  // FULL: a committed row survives a power loss, like its container file.
  MW_RETURN_IF_ERROR(catalog->Exec("PRAGMA synchronous=FULL;"));
  // A small WAL: each insert appends about 3 pages, and at SQLite's default
  // (checkpoint at 1000 pages, file never shrunk) the WAL grew to 540 KB of
  // a 1 MiB test disk, so deleting entries on a full disk freed too little
  // for the next upload. Checkpoint every 16 pages and cut the file back to
  // 64 KiB: it stays small, and frames after a checkpoint are written into
  // space the file already has (a DELETE on a full disk still commits).
  MW_RETURN_IF_ERROR(catalog->Exec("PRAGMA wal_autocheckpoint=16;"));
  MW_RETURN_IF_ERROR(catalog->Exec("PRAGMA journal_size_limit=65536;"));
  MW_RETURN_IF_ERROR(catalog->Migrate(SqliteMigrations()));
  catalog->KeepReserve();
  return catalog;
}

SqliteCatalog::~SqliteCatalog() { sqlite3_close(db_); }

Status SqliteCatalog::Exec(const char* sql) {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &message) != SQLITE_OK) {
    std::string m = message ? message : "unknown error";
    sqlite3_free(message);
    return IoError("catalog: " + m);
  }
  return Status::Ok();
}

namespace {

// The flock of ingest_lock.h as an IngestGuard.
class FlockGuard final : public IngestGuard {
 public:
  explicit FlockGuard(const std::filesystem::path& dir) : lock_(dir) {}
  const Status& status() const { return lock_.status(); }

 private:
  IngestLock lock_;
};

}  // namespace

Result<std::unique_ptr<IngestGuard>> SqliteCatalog::LockIngest() {
  auto guard = std::make_unique<FlockGuard>(store_dir());
  MW_RETURN_IF_ERROR(guard->status());
  return std::unique_ptr<IngestGuard>(std::move(guard));
}

Status SqliteCatalog::Insert(const CatalogEntry& e, const Original* original) {
  if (!IsValidMeshId(e.id)) return InvalidArgument("catalog: invalid id '" + e.id + "'");
  if (original && original->digest != e.original) {
    return Status(StatusCode::kInternal, "catalog: the original is not the entry's");
  }
  std::lock_guard lock(mutex_);
  return InTransaction([&]() -> Status {
    if (original) {
      Statement known(db_, "SELECT 1 FROM originals WHERE digest = ?;");
      if (!known.ok()) return SqlError(db_, "prepare original");
      known.Bind(1, original->digest);
      const int rc = known.Step();
      if (rc != SQLITE_ROW && rc != SQLITE_DONE) return SqlError(db_, "find original");
      if (rc == SQLITE_DONE) MW_RETURN_IF_ERROR(InsertOriginal(*original, e.created_unix));
    }
    Statement st(db_, (std::string("INSERT INTO meshes (") + kCatalogColumns +
                       ") VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?);").c_str());
    if (!st.ok()) return SqlError(db_, "prepare insert");
    st.Bind(1, e.id);
    st.Bind(2, e.name);
    st.Bind(3, e.source);
    st.Bind(4, static_cast<int64_t>(e.vertices));
    st.Bind(5, static_cast<int64_t>(e.faces));
    st.Bind(6, static_cast<int64_t>(e.levels));
    st.Bind(7, static_cast<int64_t>(e.packets));
    st.Bind(8, static_cast<int64_t>(e.bytes));
    st.Bind(9, e.container);
    st.Bind(10, e.sha256);
    st.Bind(11, e.created_unix);
    st.Bind(12, static_cast<int64_t>(e.format_version));
    st.Bind(13, e.original);
    st.Bind(14, e.settings);
    const int rc = st.Step();
    if (rc != SQLITE_DONE) {
      return rc == SQLITE_CONSTRAINT ? InvalidArgument("catalog: id " + e.id + " exists")
                                     : SqlError(db_, "insert");
    }
    return BumpGeneration();
  });
}

Status SqliteCatalog::InsertOriginal(const Original& o, int64_t created) {
  Statement st(db_, "INSERT INTO originals (digest, main, format, bytes, created) "
                    "VALUES (?,?,?,?,?);");
  if (!st.ok()) return SqlError(db_, "prepare original insert");
  st.Bind(1, o.digest);
  st.Bind(2, o.main);
  st.Bind(3, o.format);
  st.Bind(4, static_cast<int64_t>(o.bytes));
  st.Bind(5, created);
  if (st.Step() != SQLITE_DONE) return SqlError(db_, "insert original");
  for (const OriginalFile& f : o.files) {
    Statement file(db_, "INSERT INTO original_files (original, name, sha256, bytes) "
                        "VALUES (?,?,?,?);");
    if (!file.ok()) return SqlError(db_, "prepare original file insert");
    file.Bind(1, o.digest);
    file.Bind(2, f.name);
    file.Bind(3, f.sha256);
    file.Bind(4, static_cast<int64_t>(f.bytes));
    if (file.Step() != SQLITE_DONE) return SqlError(db_, "insert original file");
  }
  return Status::Ok();
}

Status SqliteCatalog::BumpGeneration() {
  return Exec("UPDATE catalog_generation SET generation = generation + 1;");
}

Status SqliteCatalog::InTransaction(const std::function<Status()>& body) {
  MW_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE;"));
  Status s = body();
  if (s.ok()) s = Exec("COMMIT;");
  if (!s.ok()) {
    failed_code_ = sqlite3_errcode(db_);  // before ROLLBACK overwrites it
    (void)Exec("ROLLBACK;");
  }
  return s;
}

Result<std::optional<CatalogEntry>> SqliteCatalog::Find(const std::string& id) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  std::lock_guard lock(mutex_);
  Statement st(db_, (std::string("SELECT ") + kCatalogColumns +
                     " FROM meshes WHERE id = ?;").c_str());
  if (!st.ok()) return SqlError(db_, "prepare find");
  st.Bind(1, id);
  const int rc = st.Step();
  if (rc == SQLITE_ROW) return std::optional<CatalogEntry>(ReadRow(st));
  if (rc == SQLITE_DONE) return std::optional<CatalogEntry>();
  return SqlError(db_, "find");
}

Result<std::vector<CatalogEntry>> SqliteCatalog::List(uint64_t limit, uint64_t offset) {
  std::lock_guard lock(mutex_);
  Statement st(db_, (std::string("SELECT ") + kCatalogColumns +
                     " FROM meshes ORDER BY created, id LIMIT ? OFFSET ?;").c_str());
  if (!st.ok()) return SqlError(db_, "prepare list");
  // SQLite integers are signed 64-bit; larger values mean "all" anyway.
  constexpr uint64_t kMax = static_cast<uint64_t>(INT64_MAX);
  st.Bind(1, static_cast<int64_t>(std::min(limit, kMax)));
  st.Bind(2, static_cast<int64_t>(std::min(offset, kMax)));
  std::vector<CatalogEntry> out;
  int rc;
  while ((rc = st.Step()) == SQLITE_ROW) out.push_back(ReadRow(st));
  if (rc != SQLITE_DONE) return SqlError(db_, "list");
  return out;
}

Result<uint64_t> SqliteCatalog::Count() {
  std::lock_guard lock(mutex_);
  Statement st(db_, "SELECT COUNT(*) FROM meshes;");
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "count");
  return static_cast<uint64_t>(st.Int(0));
}

Result<bool> SqliteCatalog::Remove(const std::string& id) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  std::lock_guard lock(mutex_);
  bool removed = false;
  for (int attempt = 0;; ++attempt) {
    Status s = InTransaction([&]() -> Status {
      Statement st(db_, "DELETE FROM meshes WHERE id = ? RETURNING original;");
      if (!st.ok()) return SqlError(db_, "prepare delete");
      st.Bind(1, id);
      std::string original;
      int rc = st.Step();
      if (rc == SQLITE_ROW) {
        original = st.Text(0);
        rc = st.Step();
      }
      if (rc != SQLITE_DONE) return SqlError(db_, "delete");
      removed = sqlite3_changes(db_) > 0;
      if (!removed) return Status::Ok();
      if (!original.empty()) {
        // The original goes with its last mesh (its blobs: ingest.h).
        Statement files(db_, "DELETE FROM original_files WHERE original = ? AND NOT EXISTS "
                             "(SELECT 1 FROM meshes WHERE original = ?);");
        Statement row(db_, "DELETE FROM originals WHERE digest = ? AND NOT EXISTS "
                           "(SELECT 1 FROM meshes WHERE original = ?);");
        if (!files.ok() || !row.ok()) return SqlError(db_, "prepare original delete");
        files.Bind(1, original);
        files.Bind(2, original);
        row.Bind(1, original);
        row.Bind(2, original);
        if (files.Step() != SQLITE_DONE || row.Step() != SQLITE_DONE) {
          return SqlError(db_, "delete original");
        }
      }
      return BumpGeneration();
    });
    if (s.ok()) break;
    // A full disk: the delete's WAL frames need a few pages. Give up the
    // reserve (deleting is how a user frees space) and try once more.
    if (attempt > 0 || failed_code_ != SQLITE_FULL || !ReleaseReserve()) return s;
  }
  KeepReserve();
  return removed;
}

std::filesystem::path SqliteCatalog::reserve_path() const {
  return store_dir() / "catalog.reserve";
}

void SqliteCatalog::KeepReserve() {
  std::error_code ec;
  if (std::filesystem::file_size(reserve_path(), ec) == kReserveBytes) return;
  // Written, not allocated sparsely: the space must really be held.
  const std::string zeros(kReserveBytes, '\0');
  {
    std::ofstream out(reserve_path(), std::ios::binary | std::ios::trunc);
    if (out.write(zeros.data(), static_cast<std::streamsize>(zeros.size())).flush()) return;
  }
  std::filesystem::remove(reserve_path(), ec);  // no room yet: try again later
}

bool SqliteCatalog::ReleaseReserve() {
  std::error_code ec;
  return std::filesystem::remove(reserve_path(), ec);
}

Result<std::vector<std::string>> SqliteCatalog::Strings(const char* sql, const std::string& what) {
  std::lock_guard lock(mutex_);
  Statement st(db_, sql);
  if (!st.ok()) return SqlError(db_, "prepare " + what);
  std::vector<std::string> out;
  int rc;
  while ((rc = st.Step()) == SQLITE_ROW) out.push_back(st.Text(0));
  if (rc != SQLITE_DONE) return SqlError(db_, what);
  return out;
}

Result<std::vector<std::string>> SqliteCatalog::ContainerPaths() {
  return Strings("SELECT container FROM meshes UNION SELECT container FROM retired_containers;",
                 "container paths");
}

Result<std::vector<std::string>> SqliteCatalog::OriginalBlobs() {
  return Strings("SELECT DISTINCT sha256 FROM original_files;", "original blobs");
}

Result<std::optional<Original>> SqliteCatalog::FindOriginal(const std::string& digest) {
  std::lock_guard lock(mutex_);
  Statement st(db_, "SELECT main, format, bytes FROM originals WHERE digest = ?;");
  if (!st.ok()) return SqlError(db_, "prepare original");
  st.Bind(1, digest);
  const int rc = st.Step();
  if (rc == SQLITE_DONE) return std::optional<Original>();
  if (rc != SQLITE_ROW) return SqlError(db_, "find original");
  Original o;
  o.digest = digest;
  o.main = st.Text(0);
  o.format = st.Text(1);
  o.bytes = static_cast<uint64_t>(st.Int(2));
  Statement files(db_, "SELECT name, sha256, bytes FROM original_files WHERE original = ? "
                       "ORDER BY name;");
  if (!files.ok()) return SqlError(db_, "prepare original files");
  files.Bind(1, digest);
  int frc;
  while ((frc = files.Step()) == SQLITE_ROW) {
    o.files.push_back({files.Text(0), files.Text(1), static_cast<uint64_t>(files.Int(2))});
  }
  if (frc != SQLITE_DONE) return SqlError(db_, "original files");
  return std::optional<Original>(std::move(o));
}

Result<bool> SqliteCatalog::ReplaceContainer(const std::string& id, const std::string& old_sha256,
                                             const CatalogEntry& now, int64_t retired_unix) {
  if (!IsValidMeshId(id)) return InvalidArgument("catalog: invalid id");
  std::lock_guard lock(mutex_);
  bool replaced = false;
  if (Status done = InTransaction([&]() -> Status {
    Statement old(db_, "SELECT container FROM meshes WHERE id = ? AND sha256 = ?;");
    if (!old.ok()) return SqlError(db_, "prepare swap");
    old.Bind(1, id);
    old.Bind(2, old_sha256);
    const int rc = old.Step();
    if (rc == SQLITE_DONE) return Status::Ok();
    if (rc != SQLITE_ROW) return SqlError(db_, "swap");
    const std::string old_container = old.Text(0);
    Statement st(db_, "UPDATE meshes SET vertices = ?, faces = ?, levels = ?, packets = ?, "
                      "bytes = ?, container = ?, sha256 = ?, format_version = ?, settings = ? "
                      "WHERE id = ?;");
    if (!st.ok()) return SqlError(db_, "prepare swap update");
    st.Bind(1, static_cast<int64_t>(now.vertices));
    st.Bind(2, static_cast<int64_t>(now.faces));
    st.Bind(3, static_cast<int64_t>(now.levels));
    st.Bind(4, static_cast<int64_t>(now.packets));
    st.Bind(5, static_cast<int64_t>(now.bytes));
    st.Bind(6, now.container);
    st.Bind(7, now.sha256);
    st.Bind(8, static_cast<int64_t>(now.format_version));
    st.Bind(9, now.settings);
    st.Bind(10, id);
    if (st.Step() != SQLITE_DONE) return SqlError(db_, "swap update");
    if (old_container != now.container) {
      Statement retire(db_, "INSERT INTO retired_containers (container, retired) VALUES (?, ?) "
                            "ON CONFLICT (container) DO UPDATE SET retired = excluded.retired;");
      if (!retire.ok()) return SqlError(db_, "prepare retire");
      retire.Bind(1, old_container);
      retire.Bind(2, retired_unix);
      if (retire.Step() != SQLITE_DONE) return SqlError(db_, "retire");
    }
    replaced = true;
    return BumpGeneration();
  }); !done.ok()) {
    return done;
  }
  return replaced;
}

Result<std::vector<std::string>> SqliteCatalog::ExpireRetired(int64_t before_unix) {
  std::lock_guard lock(mutex_);
  std::vector<std::string> expired;
  if (Status done = InTransaction([&]() -> Status {
    Statement st(db_, "DELETE FROM retired_containers WHERE retired < ? RETURNING container;");
    if (!st.ok()) return SqlError(db_, "prepare expire");
    st.Bind(1, before_unix);
    int rc;
    while ((rc = st.Step()) == SQLITE_ROW) expired.push_back(st.Text(0));
    if (rc != SQLITE_DONE) return SqlError(db_, "expire");
    return Status::Ok();
  }); !done.ok()) {
    return done;
  }
  // A container a row names again (the same bytes made anew) stays.
  std::vector<std::string> out;
  for (std::string& path : expired) {
    Statement used(db_, "SELECT 1 FROM meshes WHERE container = ?;");
    if (!used.ok()) return SqlError(db_, "prepare expire check");
    used.Bind(1, path);
    const int rc = used.Step();
    if (rc == SQLITE_DONE) out.push_back(std::move(path));
    else if (rc != SQLITE_ROW) return SqlError(db_, "expire check");
  }
  return out;
}

Result<int64_t> SqliteCatalog::Generation() {
  std::lock_guard lock(mutex_);
  Statement st(db_, "SELECT generation FROM catalog_generation;");
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "generation");
  return st.Int(0);
}

Status SqliteCatalog::Migrate(const std::vector<Migration>& migrations) {
  // Several processes may open a catalog at once: each migration runs in
  // a write transaction that reads the version again.
  for (const Migration& m : migrations) {
    if (Status done = InTransaction([&]() -> Status {
      Statement version(db_, "PRAGMA user_version;");
      if (!version.ok() || version.Step() != SQLITE_ROW) return SqlError(db_, "schema version");
      const int64_t current = version.Int(0);
      const int newest = migrations.back().version;
      if (current > newest) {
        return Status(StatusCode::kUnsupported,
                      "catalog: the schema of " + (store_dir() / "catalog.db").string() +
                          " is at version " + std::to_string(current) +
                          ", newer than this server knows (" + std::to_string(newest) +
                          "): upgrade meshwave-server");
      }
      if (current >= m.version) return Status::Ok();
      MW_RETURN_IF_ERROR(Exec(std::string(m.sql).c_str()).WithContext(std::string(m.name)));
      return Exec(("PRAGMA user_version = " + std::to_string(m.version) + ";").c_str());
    }); !done.ok()) {
      return done;
    }
  }
  return Status::Ok();
}

Result<std::string> SqliteCatalog::JournalMode() {
  std::lock_guard lock(mutex_);
  Statement st(db_, "PRAGMA journal_mode;");
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "journal mode");
  return st.Text(0);
}

}  // namespace meshwave::server
