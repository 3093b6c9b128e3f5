// Bulk ingest: which files a folder or a list names, how they split into
// shards, and parallel ingest that a rerun finds already done.
#include "bulk_ingest.h"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "server/catalog_backends_testonly.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

using meshwave::testing::CatalogBackend;
using meshwave::testing::CatalogBackendTest;
using meshwave::testing::SampleMesh;
using meshwave::testing::TempDir;

void Touch(const std::filesystem::path& p) {
  std::filesystem::create_directories(p.parent_path());
  std::ofstream(p) << "x";
}

TEST(BulkIngestTest, CollectsMeshFilesFromFoldersAndLists) {
  TempDir tmp;
  Touch(tmp / "in/a.ply");
  Touch(tmp / "in/sub/b.OBJ");
  Touch(tmp / "in/sub/deeper/c.off");
  Touch(tmp / "in/readme.txt");
  Touch(tmp / "other/d.ply");
  std::ofstream(tmp / "list.txt") << "# meshes\n\nother/d.ply\n" << (tmp / "in/a.ply").string()
                                  << "\n";
  auto files = CollectMeshFiles({(tmp / "in").string()}, (tmp / "list.txt").string());
  ASSERT_TRUE(files.ok()) << files.status().ToString();
  ASSERT_EQ(files->size(), 4u);  // a.ply once, readme.txt not at all
  std::set<std::string> names;
  for (const auto& f : *files) names.insert(f.filename().string());
  EXPECT_EQ(names, (std::set<std::string>{"a.ply", "b.OBJ", "c.off", "d.ply"}));
  EXPECT_TRUE(std::is_sorted(files->begin(), files->end()));

  auto missing = CollectMeshFiles({(tmp / "nope").string()}, "");
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_FALSE(CollectMeshFiles({}, (tmp / "no-list.txt").string()).ok());
}

TEST(BulkIngestTest, ParsesShards) {
  EXPECT_EQ(ParseShard("0/1")->count, 1u);
  EXPECT_EQ(ParseShard("3/8")->index, 3u);
  for (const char* bad : {"", "1", "1/1", "2/1", "0/0", "a/b", "-1/4", "1/4/2"}) {
    EXPECT_FALSE(ParseShard(bad).ok()) << bad;
  }
}

TEST(BulkIngestTest, ShardsPartitionTheFiles) {
  std::vector<std::filesystem::path> files;
  for (int i = 0; i < 500; ++i) files.push_back("/meshes/m" + std::to_string(i) + ".ply");
  std::set<std::filesystem::path> seen;
  for (uint32_t i = 0; i < 4; ++i) {
    const auto part = FilesOfShard(files, {i, 4});
    EXPECT_GT(part.size(), 80u);  // roughly a quarter each
    for (const auto& f : part) EXPECT_TRUE(seen.insert(f).second) << f << " in two shards";
  }
  EXPECT_EQ(seen.size(), files.size());
  // A file's shard does not depend on what else is listed.
  const auto alone = FilesOfShard({files[7]}, {0, 4});
  const auto part0 = FilesOfShard(files, {0, 4});
  EXPECT_EQ(alone.size() == 1,
            std::find(part0.begin(), part0.end(), files[7]) != part0.end());
}

using BulkIngestBackendTest = CatalogBackendTest;

TEST_P(BulkIngestBackendTest, ParallelIngestAndIdempotentRerun) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  const std::vector<std::filesystem::path> files = {
      tmp_ / "holes_copy.off", SampleMesh("holes.off"), tmp_ / "broken.ply"};
  // Another name, another container (the name is in the header).
  std::filesystem::copy_file(SampleMesh("holes.off"), tmp_ / "holes_copy.off");
  std::ofstream(tmp_ / "broken.ply") << "ply\nformat ascii 1.0\nelement vertex 99999999\n";
  std::vector<std::string> reported;
  size_t present = 0;
  auto report = [&](const std::filesystem::path& f, const Result<IngestResult>& r) {
    reported.push_back(f.filename().string());
    if (r.ok() && r->already_present) ++present;
  };
  EXPECT_EQ(IngestFiles(*catalog, files, 2, "", report), 1u);  // broken.ply
  EXPECT_EQ(reported.size(), 3u);
  EXPECT_EQ(present, 0u);
  EXPECT_EQ(*catalog->Count(), 2u);

  // The rerun, as a retried Job worker on another replica would do it.
  auto again = OpenCatalog();
  ASSERT_TRUE(again);
  present = 0;
  EXPECT_EQ(IngestFiles(*again, files, 3, "", report), 1u);
  EXPECT_EQ(present, 2u);
  EXPECT_EQ(*again->Count(), 2u);
}

INSTANTIATE_TEST_SUITE_P(Backends, BulkIngestBackendTest,
                         ::testing::Values(CatalogBackend::kSqlite, CatalogBackend::kPostgres),
                         meshwave::testing::CatalogBackendName);

}  // namespace
}  // namespace meshwave::server
