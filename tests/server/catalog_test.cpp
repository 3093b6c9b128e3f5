// The SQLite catalog: creation in WAL mode, insert/find/list/remove, ids.
#include "catalog.h"

#include <gtest/gtest.h>

#include "e2e/cli_runner.h"

namespace meshwave::server {
namespace {

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

TEST(CatalogTest, CreatesMissingDirectoryInWalMode) {
  TempDir tmp;
  auto catalog = Catalog::Open(tmp / "new/catalog");
  ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
  EXPECT_TRUE(std::filesystem::is_directory(tmp / "new/catalog/containers"));
  EXPECT_TRUE(std::filesystem::exists(tmp / "new/catalog/catalog.db"));
  EXPECT_EQ(*(*catalog)->JournalMode(), "wal");
  EXPECT_EQ(*(*catalog)->Count(), 0u);
}

TEST(CatalogTest, InsertsFindsListsAndRemoves) {
  TempDir tmp;
  auto catalog = Catalog::Open(tmp / "c").value();
  ASSERT_TRUE(catalog->Insert(Entry("00000000000b", 2)).ok());
  ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  ASSERT_TRUE(catalog->Insert(Entry("00000000000c", 3)).ok());
  EXPECT_EQ(*catalog->Count(), 3u);

  auto found = catalog->Find("00000000000b");
  ASSERT_TRUE(found.ok());
  ASSERT_TRUE(found->has_value());
  EXPECT_EQ((*found)->name, "mesh 00000000000b");
  EXPECT_EQ((*found)->bytes, 1234u);
  EXPECT_EQ((*found)->container, "containers/00000000000b.mwv");
  EXPECT_FALSE(catalog->Find("ffffffffffff")->has_value());

  auto all = *catalog->List(10, 0);
  ASSERT_EQ(all.size(), 3u);  // by creation time
  EXPECT_EQ(all[0].id, "00000000000a");
  EXPECT_EQ(all[2].id, "00000000000c");
  auto page = *catalog->List(1, 1);
  ASSERT_EQ(page.size(), 1u);
  EXPECT_EQ(page[0].id, "00000000000b");
  EXPECT_TRUE(catalog->List(10, 5)->empty());
  EXPECT_EQ(catalog->ContainerPaths()->size(), 3u);

  EXPECT_TRUE(*catalog->Remove("00000000000b"));
  EXPECT_FALSE(*catalog->Remove("00000000000b"));
  EXPECT_EQ(*catalog->Count(), 2u);
}

TEST(CatalogTest, RejectsDuplicateAndInvalidIds) {
  TempDir tmp;
  auto catalog = Catalog::Open(tmp / "c").value();
  ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  EXPECT_EQ(catalog->Insert(Entry("00000000000a", 2)).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(catalog->Insert(Entry("../../etc/pa", 1)).ok());
  EXPECT_FALSE(catalog->Find("0' OR '1'='1").ok());
  EXPECT_FALSE(catalog->Remove("ABCDEF012345").ok());
  EXPECT_EQ(*catalog->Count(), 1u);
}

TEST(CatalogTest, KeepsEntriesAcrossReopening) {
  TempDir tmp;
  {
    auto catalog = Catalog::Open(tmp / "c").value();
    ASSERT_TRUE(catalog->Insert(Entry("00000000000a", 1)).ok());
  }
  auto catalog = Catalog::Open(tmp / "c").value();
  EXPECT_EQ(*catalog->Count(), 1u);
  EXPECT_EQ(*catalog->JournalMode(), "wal");
}

TEST(CatalogTest, SecondConnectionSeesCommittedRows) {
  TempDir tmp;
  auto writer = Catalog::Open(tmp / "c").value();
  auto reader = Catalog::Open(tmp / "c").value();  // as the ingest command and a server
  ASSERT_TRUE(writer->Insert(Entry("00000000000a", 1)).ok());
  EXPECT_TRUE(reader->Find("00000000000a")->has_value());
}

}  // namespace
}  // namespace meshwave::server
