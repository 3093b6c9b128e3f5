#include "sqlite_catalog.h"

#include <fstream>
#include <utility>

#include "ingest_lock.h"
#include "meshwave/mesh_id.h"

namespace meshwave::server {
namespace {

constexpr char kSchema[] = R"sql(
CREATE TABLE IF NOT EXISTS meshes (
  id TEXT PRIMARY KEY NOT NULL,
  name TEXT NOT NULL,
  source TEXT NOT NULL,
  vertices INTEGER NOT NULL,
  faces INTEGER NOT NULL,
  levels INTEGER NOT NULL,
  packets INTEGER NOT NULL,
  bytes INTEGER NOT NULL,
  container TEXT NOT NULL,
  sha256 TEXT NOT NULL,
  created INTEGER NOT NULL
);
CREATE INDEX IF NOT EXISTS meshes_by_created ON meshes (created, id);
)sql";

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
  MW_RETURN_IF_ERROR(catalog->Exec(kSchema));
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

Status SqliteCatalog::Insert(const CatalogEntry& e) {
  if (!IsValidMeshId(e.id)) return InvalidArgument("catalog: invalid id '" + e.id + "'");
  std::lock_guard lock(mutex_);
  MW_RETURN_IF_ERROR(Exec("BEGIN IMMEDIATE;"));
  Statement st(db_, (std::string("INSERT INTO meshes (") + kCatalogColumns +
                     ") VALUES (?,?,?,?,?,?,?,?,?,?,?);").c_str());
  if (!st.ok()) {
    (void)Exec("ROLLBACK;");
    return SqlError(db_, "prepare insert");
  }
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
  const int rc = st.Step();
  if (rc != SQLITE_DONE) {
    Status s = rc == SQLITE_CONSTRAINT
                   ? InvalidArgument("catalog: id " + e.id + " exists")
                   : SqlError(db_, "insert");
    (void)Exec("ROLLBACK;");
    return s;
  }
  return Exec("COMMIT;");
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
  for (int attempt = 0;; ++attempt) {
    Statement st(db_, "DELETE FROM meshes WHERE id = ?;");
    if (!st.ok()) return SqlError(db_, "prepare delete");
    st.Bind(1, id);
    if (st.Step() == SQLITE_DONE) break;
    // A full disk: the delete's WAL frames need a few pages. Give up the
    // reserve (deleting is how a user frees space) and try once more.
    if (attempt > 0 || sqlite3_errcode(db_) != SQLITE_FULL || !ReleaseReserve()) {
      return SqlError(db_, "delete");
    }
  }
  const bool removed = sqlite3_changes(db_) > 0;
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

Result<std::vector<std::string>> SqliteCatalog::ContainerPaths() {
  std::lock_guard lock(mutex_);
  Statement st(db_, "SELECT container FROM meshes;");
  if (!st.ok()) return SqlError(db_, "prepare paths");
  std::vector<std::string> out;
  int rc;
  while ((rc = st.Step()) == SQLITE_ROW) out.push_back(st.Text(0));
  if (rc != SQLITE_DONE) return SqlError(db_, "paths");
  return out;
}

Result<std::string> SqliteCatalog::JournalMode() {
  std::lock_guard lock(mutex_);
  Statement st(db_, "PRAGMA journal_mode;");
  if (!st.ok() || st.Step() != SQLITE_ROW) return SqlError(db_, "journal mode");
  return st.Text(0);
}

}  // namespace meshwave::server
