// The catalog, against both backends (SQLite and PostgreSQL): insert, find,
// list, remove, ids, persistence, several connections; then what is
// particular to each: SQLite's WAL mode, PostgreSQL's schema migrations,
// the choice of backend by location.
#include "catalog.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <algorithm>

#include "postgres_connection.h"
#include "postgres_migrations.h"
#include "server/catalog_backends_testonly.h"
#include "sqlite_catalog.h"

namespace meshwave::server {
namespace {

using meshwave::testing::CatalogBackend;
using meshwave::testing::CatalogBackendTest;
using meshwave::testing::PostgresInstance;
using meshwave::testing::TempDir;

CatalogEntry Entry(const std::string& id, int64_t created) {
  CatalogEntry e;
  e.id = id;
  e.name = "mesh " + id;
  e.source = id + ".ply";
  e.vertices = 10;
  e.faces = 16;
  e.levels = 2;
  e.packets = 5;
  e.bytes = 1234;
  e.container = "containers/" + id + ".mwv";
  e.sha256 = id + std::string(52, '0');
  e.created_unix = created;
  return e;
}

using CatalogTest = CatalogBackendTest;

TEST_P(CatalogTest, CreatesItsContainerStore) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  EXPECT_TRUE(std::filesystem::is_directory(catalog->containers_dir()));
  EXPECT_EQ(catalog->ContainerPath(Entry("00000000000a", 1)),
            catalog->store_dir() / "containers/00000000000a.mwv");
  EXPECT_EQ(*catalog->Count(), 0u);
  EXPECT_NE(catalog->Describe().find(GetParam() == CatalogBackend::kSqlite ? "sqlite" : "postgres"),
            std::string::npos);
}

TEST_P(CatalogTest, InsertsFindsListsAndRemoves) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  ASSERT_TRUE(catalog->Insert(Entry("00000000000b", 2)).ok());
  ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  ASSERT_TRUE(catalog->Insert(Entry("00000000000c", 3)).ok());
  EXPECT_EQ(*catalog->Count(), 3u);

  auto found = catalog->Find("00000000000b");
  ASSERT_TRUE(found.ok());
  ASSERT_TRUE(found->has_value());
  EXPECT_EQ((*found)->name, "mesh 00000000000b");
  EXPECT_EQ((*found)->source, "00000000000b.ply");
  EXPECT_EQ((*found)->vertices, 10u);
  EXPECT_EQ((*found)->faces, 16u);
  EXPECT_EQ((*found)->levels, 2u);
  EXPECT_EQ((*found)->packets, 5u);
  EXPECT_EQ((*found)->bytes, 1234u);
  EXPECT_EQ((*found)->container, "containers/00000000000b.mwv");
  EXPECT_EQ((*found)->sha256, "00000000000b" + std::string(52, '0'));
  EXPECT_EQ((*found)->created_unix, 2);
  EXPECT_FALSE(catalog->Find("ffffffffffff")->has_value());

  auto all = *catalog->List(10, 0);
  ASSERT_EQ(all.size(), 3u);  // by creation time
  EXPECT_EQ(all[0].id, "00000000000a");
  EXPECT_EQ(all[2].id, "00000000000c");
  auto page = *catalog->List(1, 1);
  ASSERT_EQ(page.size(), 1u);
  EXPECT_EQ(page[0].id, "00000000000b");
  EXPECT_TRUE(catalog->List(10, 5)->empty());
  EXPECT_EQ(catalog->List(UINT64_MAX, 0)->size(), 3u);
  EXPECT_EQ(catalog->ContainerPaths()->size(), 3u);

  EXPECT_TRUE(*catalog->Remove("00000000000b"));
  EXPECT_FALSE(*catalog->Remove("00000000000b"));
  EXPECT_EQ(*catalog->Count(), 2u);
}

TEST_P(CatalogTest, KeepsTextAsItIs) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  CatalogEntry e = Entry("00000000000a", 1);
  e.name = "l'éléphant \"quoted\" ; DROP TABLE meshes; --";
  ASSERT_TRUE(catalog->Insert(e).ok());
  EXPECT_EQ((*catalog->Find(e.id))->name, e.name);
  EXPECT_EQ(*catalog->Count(), 1u);
}

TEST_P(CatalogTest, RejectsDuplicateAndInvalidIds) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  EXPECT_EQ(catalog->Insert(Entry("00000000000a", 2)).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(catalog->Insert(Entry("../../etc/pa", 1)).ok());
  EXPECT_FALSE(catalog->Find("0' OR '1'='1").ok());
  EXPECT_FALSE(catalog->Remove("ABCDEF012345").ok());
  EXPECT_EQ(*catalog->Count(), 1u);
}

TEST_P(CatalogTest, KeepsEntriesAcrossReopening) {
  {
    auto catalog = OpenCatalog();
    ASSERT_TRUE(catalog);
    ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  }
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  EXPECT_EQ(*catalog->Count(), 1u);
}

TEST_P(CatalogTest, SecondConnectionSeesCommittedRows) {
  auto writer = OpenCatalog();
  auto reader = OpenCatalog();  // as the ingest command and a server, or two replicas
  ASSERT_TRUE(writer && reader);
  ASSERT_TRUE(writer->Insert(Entry("00000000000a", 1)).ok());
  EXPECT_TRUE(reader->Find("00000000000a")->has_value());
  EXPECT_EQ(reader->Insert(Entry("00000000000a", 1)).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(*reader->Remove("00000000000a"));
  EXPECT_FALSE(writer->Find("00000000000a")->has_value());
}

TEST_P(CatalogTest, IngestLockExcludesOtherHandles) {
  auto a = OpenCatalog();
  auto b = OpenCatalog();
  ASSERT_TRUE(a && b);
  auto held = a->LockIngest();
  ASSERT_TRUE(held.ok()) << held.status().ToString();
  std::atomic<bool> acquired{false};
  std::thread other([&] {
    auto lock = b->LockIngest();
    EXPECT_TRUE(lock.ok());
    acquired = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_FALSE(acquired);  // waits for the first
  held->reset();
  other.join();
  EXPECT_TRUE(acquired);
}

TEST_P(CatalogTest, KeepsOriginalsWithTheirMeshes) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  const Original original =
      DescribeOriginal({{"cow.obj", "v 0 0 0"}, {"tex/cow.png", "PNG"}}, "cow.obj").value();
  CatalogEntry a = Entry("00000000000a", 1);
  a.original = original.digest;
  a.settings = "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=4096 split=48";
  a.format_version = 7;
  CatalogEntry b = Entry("00000000000b", 2);
  b.original = original.digest;  // the same upload under another name
  ASSERT_TRUE(catalog->Insert(a, &original).ok());
  ASSERT_TRUE(catalog->Insert(b, &original).ok());  // its rows are there already
  CatalogEntry wrong = Entry("00000000000c", 3);
  EXPECT_EQ(catalog->Insert(wrong, &original).code(), StatusCode::kInternal);  // not its original

  auto found = catalog->Find(a.id);
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->original, original.digest);
  EXPECT_EQ((*found)->settings, a.settings);
  EXPECT_EQ((*found)->format_version, 7u);
  auto back = catalog->FindOriginal(original.digest);
  ASSERT_TRUE(back.ok() && back->has_value()) << back.status().ToString();
  EXPECT_EQ((*back)->main, "cow.obj");
  EXPECT_EQ((*back)->format, "obj");
  EXPECT_EQ((*back)->bytes, original.bytes);
  ASSERT_EQ((*back)->files.size(), 2u);
  EXPECT_EQ((*back)->files[1].name, "tex/cow.png");
  EXPECT_EQ((*back)->files[1].sha256, original.files[1].sha256);
  EXPECT_EQ(catalog->OriginalBlobs()->size(), 2u);

  // The original goes with its last mesh.
  EXPECT_TRUE(*catalog->Remove(a.id));
  EXPECT_TRUE(catalog->FindOriginal(original.digest)->has_value());
  EXPECT_TRUE(*catalog->Remove(b.id));
  EXPECT_FALSE(catalog->FindOriginal(original.digest)->has_value());
  EXPECT_TRUE(catalog->OriginalBlobs()->empty());
}

TEST_P(CatalogTest, SwapsContainersAndKeepsTheOldOnesRetired) {
  auto catalog = OpenCatalog();
  auto other = OpenCatalog();  // another replica
  ASSERT_TRUE(catalog && other);
  const CatalogEntry before = Entry("00000000000a", 5);
  ASSERT_TRUE(catalog->Insert(before).ok());
  const int64_t g0 = *other->Generation();

  CatalogEntry now = Entry("00000000000a", 99);
  now.sha256 = std::string(64, 'f');
  now.container = "containers/" + now.sha256 + ".mwv";
  now.bytes = 4321;
  now.format_version = 7;
  now.settings = "fidelity=84 max_vertex_ratio=4 remesh=auto precinct=1024 split=48";
  now.name = "ignored";  // the id, name, source, original and time stay
  // Only when the row still names the container it was made from.
  EXPECT_FALSE(*catalog->ReplaceContainer(before.id, std::string(64, '1'), now, 100));
  EXPECT_EQ(*other->Generation(), g0);
  EXPECT_TRUE(*catalog->ReplaceContainer(before.id, before.sha256, now, 100));
  EXPECT_GT(*other->Generation(), g0);
  auto row = other->Find(before.id);
  ASSERT_TRUE(row.ok() && row->has_value());
  EXPECT_EQ((*row)->sha256, now.sha256);
  EXPECT_EQ((*row)->container, now.container);
  EXPECT_EQ((*row)->bytes, 4321u);
  EXPECT_EQ((*row)->format_version, 7u);
  EXPECT_EQ((*row)->settings, now.settings);
  EXPECT_EQ((*row)->name, before.name);
  EXPECT_EQ((*row)->created_unix, 5);
  // The old container stays among the paths to keep until it expires.
  auto paths = other->ContainerPaths();
  ASSERT_TRUE(paths.ok());
  EXPECT_EQ(paths->size(), 2u);
  EXPECT_NE(std::find(paths->begin(), paths->end(), before.container), paths->end());
  EXPECT_TRUE(other->ExpireRetired(100)->empty());  // retired at 100: not before it
  auto expired = other->ExpireRetired(101);
  ASSERT_TRUE(expired.ok());
  ASSERT_EQ(expired->size(), 1u);
  EXPECT_EQ((*expired)[0], before.container);
  EXPECT_EQ(other->ContainerPaths()->size(), 1u);
  // A deleted mesh cannot be swapped.
  EXPECT_TRUE(*catalog->Remove(before.id));
  EXPECT_FALSE(*catalog->ReplaceContainer(before.id, now.sha256, before, 200));
}

TEST_P(CatalogTest, GenerationMovesWithEveryChange) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  const int64_t g0 = *catalog->Generation();
  ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  const int64_t g1 = *catalog->Generation();
  EXPECT_GT(g1, g0);
  EXPECT_FALSE(*catalog->Remove("00000000000b"));  // nothing removed
  EXPECT_EQ(*catalog->Generation(), g1);
  EXPECT_TRUE(*catalog->Remove("00000000000a"));
  EXPECT_GT(*catalog->Generation(), g1);
}

INSTANTIATE_TEST_SUITE_P(Backends, CatalogTest,
                         ::testing::Values(CatalogBackend::kSqlite, CatalogBackend::kPostgres),
                         meshwave::testing::CatalogBackendName);

// --- SQLite only --------------------------------------------------------

// A catalog made before its schema was versioned (the meshes table alone,
// user_version 0) is migrated on open, its rows kept.
TEST(SqliteCatalogTest, MigratesACatalogFromBeforeVersionedSchemas) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "old");
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((tmp / "old/catalog.db").c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db,
                           "CREATE TABLE meshes (id TEXT PRIMARY KEY NOT NULL, name TEXT NOT NULL, "
                           "source TEXT NOT NULL, vertices INTEGER NOT NULL, faces INTEGER NOT "
                           "NULL, levels INTEGER NOT NULL, packets INTEGER NOT NULL, bytes "
                           "INTEGER NOT NULL, container TEXT NOT NULL, sha256 TEXT NOT NULL, "
                           "created INTEGER NOT NULL);"
                           "INSERT INTO meshes VALUES ('00000000000a', 'old', 'old.off', 1, 2, 3, "
                           "4, 5, 'containers/x.mwv', 'x', 6);",
                           nullptr, nullptr, nullptr),
              SQLITE_OK);
    sqlite3_close(db);
  }
  auto catalog = SqliteCatalog::Open(tmp / "old");
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  auto row = (*catalog)->Find("00000000000a");
  ASSERT_TRUE(row.ok() && row->has_value());
  EXPECT_EQ((*row)->name, "old");
  EXPECT_EQ((*row)->format_version, 0u);  // not recorded then
  EXPECT_TRUE((*row)->original.empty());
  EXPECT_TRUE((*catalog)->Generation().ok());
  catalog->reset();
  // Opening again applies nothing twice.
  EXPECT_TRUE(SqliteCatalog::Open(tmp / "old").ok());
}

TEST(SqliteCatalogTest, RefusesASchemaNewerThanTheBinary) {
  TempDir tmp;
  ASSERT_TRUE(SqliteCatalog::Open(tmp / "c").ok());
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open((tmp / "c/catalog.db").c_str(), &db), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(db, "PRAGMA user_version = 999;", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
  }
  auto catalog = SqliteCatalog::Open(tmp / "c");
  ASSERT_FALSE(catalog.ok());
  EXPECT_EQ(catalog.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(catalog.status().message().find("upgrade meshwave-server"), std::string::npos);
}

TEST(SqliteCatalogTest, CreatesMissingDirectoryInWalMode) {
  TempDir tmp;
  auto catalog = SqliteCatalog::Open(tmp / "new/catalog");
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  EXPECT_TRUE(std::filesystem::is_directory(tmp / "new/catalog/containers"));
  EXPECT_TRUE(std::filesystem::exists(tmp / "new/catalog/catalog.db"));
  EXPECT_EQ(*(*catalog)->JournalMode(), "wal");
  auto again = SqliteCatalog::Open(tmp / "new/catalog");
  EXPECT_EQ(*(*again)->JournalMode(), "wal");
}

// The reserve a DELETE on a full disk takes (the disk-full fault test
// fills a tmpfs for real): held as written bytes, and back after a delete.
TEST(SqliteCatalogTest, HoldsAReserveAndKeepsItAfterDeletes) {
  TempDir tmp;
  auto catalog = SqliteCatalog::Open(tmp / "c");
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  const auto reserve = tmp / "c/catalog.reserve";
  ASSERT_TRUE(std::filesystem::exists(reserve));
  EXPECT_EQ(std::filesystem::file_size(reserve), 128u * 1024);
  ASSERT_TRUE((*catalog)->Insert(Entry("00000000000a", 1)).ok());
  std::filesystem::remove(reserve);  // as a delete on a full disk leaves it
  EXPECT_TRUE(*(*catalog)->Remove("00000000000a"));
  EXPECT_EQ(std::filesystem::file_size(reserve), 128u * 1024);
}

// --- choosing the backend ---------------------------------------------

TEST(CatalogOpenTest, ChoosesTheBackendByLocation) {
  EXPECT_TRUE(Catalog::IsPostgresUri("postgres://u@h:5432/db"));
  EXPECT_TRUE(Catalog::IsPostgresUri("postgresql://h/db"));
  EXPECT_FALSE(Catalog::IsPostgresUri("/var/lib/meshwave"));
  EXPECT_FALSE(Catalog::IsPostgresUri("postgres"));  // a directory of that name
  TempDir tmp;
  auto no_store = Catalog::Open("postgres://u@127.0.0.1:1/db");
  ASSERT_FALSE(no_store.ok());
  EXPECT_NE(no_store.status().message().find("--store"), std::string::npos);
  auto store_with_sqlite = Catalog::Open((tmp / "c").string(), tmp / "store");
  ASSERT_FALSE(store_with_sqlite.ok());
  EXPECT_NE(store_with_sqlite.status().message().find("only for a postgres"), std::string::npos);
  EXPECT_FALSE(Catalog::Open("").ok());
}

TEST(CatalogOpenTest, UnreachablePostgresIsAClearError) {
  TempDir tmp;
  const uint16_t port = meshwave::testing::FreeLoopbackPort();  // nothing listens
  auto catalog = Catalog::Open("postgres://meshwave:secret@127.0.0.1:" + std::to_string(port) +
                                   "/db?connect_timeout=2",
                               tmp / "store");
  ASSERT_FALSE(catalog.ok());
  const std::string m = catalog.status().message();
  EXPECT_NE(m.find("cannot connect to postgres://meshwave@127.0.0.1:" + std::to_string(port) +
                   "/db"),
            std::string::npos)
      << m;
  EXPECT_EQ(m.find("secret"), std::string::npos) << m;  // never the password
}

// --- PostgreSQL schema migrations ---------------------------------------

class PostgresMigrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const std::string why = meshwave::testing::PostgresUnavailableReason(); !why.empty()) {
      if (std::getenv("CI") != nullptr) FAIL() << why << " (CI must run the PostgreSQL tests)";
      GTEST_SKIP() << why;
    }
    ASSERT_TRUE(pg_.ok()) << pg_.error();
    auto conn = PostgresConnection::Connect(pg_.Uri());
    ASSERT_TRUE(conn.ok()) << conn.status().ToString();
    conn_ = std::move(*conn);
  }
  PostgresInstance pg_;
  std::unique_ptr<PostgresConnection> conn_;
};

TEST_F(PostgresMigrationTest, RepositoryMigrationsAreNumberedFromOne) {
  const auto& all = PostgresMigrations();
  ASSERT_FALSE(all.empty());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].version, static_cast<int>(i) + 1) << all[i].name;
    EXPECT_FALSE(all[i].sql.empty());
  }
  EXPECT_EQ(all[0].name, "0001_init.sql");
}

TEST_F(PostgresMigrationTest, AppliesEachMigrationOnceAndRecordsIt) {
  ASSERT_TRUE(MigrateSchema(*conn_, PostgresMigrations()).ok());
  ASSERT_TRUE(MigrateSchema(*conn_, PostgresMigrations()).ok());  // nothing left to do
  EXPECT_EQ(*SchemaVersion(*conn_), static_cast<int>(PostgresMigrations().size()));
  auto rows = conn_->Exec("SELECT count(*) FROM schema_version");
  ASSERT_TRUE(rows.ok());
  EXPECT_EQ(rows->Text(0, 0), std::to_string(PostgresMigrations().size()));

  // A later migration applies on top, in order.
  std::vector<Migration> more = PostgresMigrations();
  more.push_back({static_cast<int>(more.size()) + 1, "9999_test.sql",
                  "ALTER TABLE meshes ADD COLUMN note text; CREATE INDEX by_note ON meshes (note);"});
  ASSERT_TRUE(MigrateSchema(*conn_, more).ok());
  EXPECT_EQ(*SchemaVersion(*conn_), static_cast<int>(more.size()));
  EXPECT_TRUE(conn_->Exec("SELECT note FROM meshes").ok());
}

TEST_F(PostgresMigrationTest, AFailingMigrationChangesNothing) {
  std::vector<Migration> broken = PostgresMigrations();
  broken.push_back({static_cast<int>(broken.size()) + 1, "0099_broken.sql",
                    "CREATE TABLE half (x int); SELECT no_such_function();"});
  const Status s = MigrateSchema(*conn_, broken);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("0099_broken.sql"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("no_such_function"), std::string::npos) << s.message();
  // Not even the earlier migrations of the same run: one transaction.
  EXPECT_FALSE(conn_->Exec("SELECT 1 FROM meshes").ok());
  EXPECT_FALSE(conn_->Exec("SELECT 1 FROM half").ok());
}

TEST_F(PostgresMigrationTest, RefusesADatabaseNewerThanTheBinary) {
  ASSERT_TRUE(MigrateSchema(*conn_, PostgresMigrations()).ok());
  ASSERT_TRUE(conn_->Exec("INSERT INTO schema_version (version, name) VALUES (999, 'future')").ok());
  TempDir tmp;
  auto catalog = Catalog::Open(pg_.Uri(), tmp / "store");
  ASSERT_FALSE(catalog.ok());
  EXPECT_EQ(catalog.status().code(), StatusCode::kUnsupported);
  EXPECT_NE(catalog.status().message().find("version 999"), std::string::npos);
}

TEST_F(PostgresMigrationTest, RejectsMigrationsOutOfSequence) {
  std::vector<Migration> gap = {{1, "0001_a.sql", "SELECT 1"}, {3, "0003_c.sql", "SELECT 1"}};
  const Status s = MigrateSchema(*conn_, gap);
  EXPECT_EQ(s.code(), StatusCode::kInternal);
  EXPECT_NE(s.message().find("0003_c.sql"), std::string::npos);
}

TEST_F(PostgresMigrationTest, ConstraintsGuardTheTable) {
  ASSERT_TRUE(MigrateSchema(*conn_, PostgresMigrations()).ok());
  // What the code checks, the schema checks too: a bad id or digest
  // inserted by hand is refused.
  EXPECT_FALSE(conn_->Exec("INSERT INTO meshes VALUES ('../x', 'n', 's', 1, 1, 1, 1, 1, "
                           "'c', repeat('0', 64), 0)")
                   .ok());
  EXPECT_FALSE(conn_->Exec("INSERT INTO meshes VALUES ('00000000000a', 'n', 's', 1, 1, 1, 1, "
                           "1, 'c', 'nothex', 0)")
                   .ok());
}

TEST_F(PostgresMigrationTest, ReconnectsAfterTheConnectionIsKilled) {
  TempDir tmp;
  auto catalog = Catalog::Open(pg_.Uri(), tmp / "store");
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  ASSERT_TRUE((*catalog)->Insert(Entry("00000000000a", 1)).ok());
  // Ends every other session, as a database restart or failover would.
  ASSERT_TRUE(conn_->Exec("SELECT pg_terminate_backend(pid) FROM pg_stat_activity "
                          "WHERE pid <> pg_backend_pid() AND datname = current_database()")
                  .ok());
  auto found = (*catalog)->Find("00000000000a");
  ASSERT_TRUE(found.ok()) << found.status().ToString();
  EXPECT_TRUE(found->has_value());
}

}  // namespace
}  // namespace meshwave::server
