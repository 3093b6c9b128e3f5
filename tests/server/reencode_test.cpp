// Re-encoding from originals, against both catalog backends: a mesh made
// with other settings gets a new container with the same id, the old one
// stays on disk retired; a second run has nothing to do; a dry run changes
// nothing; a damaged original fails that mesh alone and leaves its row.
#include "reencode.h"

#include <gtest/gtest.h>

#include <fstream>

#include "e2e/cli_runner.h"
#include "ingest.h"
#include "meshwave/container.h"
#include "server/catalog_backends_testonly.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

using meshwave::testing::CatalogBackendTest;
using meshwave::testing::ReadBytes;
using meshwave::testing::SampleMesh;

using ReencodeTest = CatalogBackendTest;

std::vector<ReencodeStep> Reencode(Catalog& catalog, const ReencodeOptions& options,
                              ReencodeReport* report = nullptr) {
  std::vector<ReencodeStep> steps;
  auto r = ReencodeCatalog(catalog, options,
                           [&](size_t, size_t, const ReencodeStep& s) { steps.push_back(s); });
  EXPECT_TRUE(r.ok()) << r.status().ToString();
  if (report && r.ok()) *report = *r;
  return steps;
}

TEST_P(ReencodeTest, NewSettingsGiveANewContainerUnderTheSameId) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto ingested = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(ingested.ok()) << ingested.status().ToString();
  const CatalogEntry before = ingested->entry;
  EXPECT_EQ(before.format_version, kStreamFormatVersion);
  EXPECT_FALSE(before.original.empty());

  // Nothing is out of date at the settings it was made with.
  ReencodeReport report;
  auto steps = Reencode(*catalog, {}, &report);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].action, ReencodeAction::kCurrent);
  EXPECT_EQ(report.current, 1u);

  ReencodeOptions smaller;
  smaller.change.precinct_coefficients = 64;
  smaller.dry_run = true;
  steps = Reencode(*catalog, smaller);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].action, ReencodeAction::kWouldReencode);
  EXPECT_NE(steps[0].why.find("precinct=64"), std::string::npos) << steps[0].why;
  EXPECT_EQ((*catalog->Find(before.id))->sha256, before.sha256);

  smaller.dry_run = false;
  steps = Reencode(*catalog, smaller, &report);
  ASSERT_EQ(steps.size(), 1u);
  ASSERT_EQ(steps[0].action, ReencodeAction::kReencoded) << steps[0].why;
  EXPECT_EQ(report.reencoded, 1u);
  auto after = catalog->Find(before.id);
  ASSERT_TRUE(after.ok() && after->has_value());
  EXPECT_NE((*after)->sha256, before.sha256);
  EXPECT_EQ((*after)->name, before.name);
  EXPECT_EQ((*after)->original, before.original);
  EXPECT_NE((*after)->settings.find("precinct=64"), std::string::npos);
  // The new container is whole and holds the new precincts; the old one
  // is still on disk for readers that may open it.
  const std::string bytes = ReadBytes(catalog->ContainerPath(**after));
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  EXPECT_EQ(parsed->header.packets.precinct_coefficients, 64u);
  EXPECT_TRUE(std::filesystem::exists(catalog->ContainerPath(before)));
  // Past the retired time a cleanup removes it, and nothing else.
  auto cleanup = RemoveOrphans(*catalog, /*retired_seconds=*/-10);
  ASSERT_TRUE(cleanup.ok());
  EXPECT_EQ(cleanup->expired_containers, 1u);
  EXPECT_FALSE(std::filesystem::exists(catalog->ContainerPath(before)));
  EXPECT_TRUE(std::filesystem::exists(catalog->ContainerPath(**after)));
  EXPECT_EQ(cleanup->orphan_originals, 0u);

  // Done: a second run finds it current.
  steps = Reencode(*catalog, smaller);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].action, ReencodeAction::kCurrent);
}

TEST_P(ReencodeTest, ADamagedOriginalFailsThatMeshAloneAndChangesNothing) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto holes = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  auto other = IngestMeshFile(*catalog, SampleMesh("elephant.off"), "", [] {
    EncodeChoices one_remesh;  // the remesh is not what this test is about
    one_remesh.fidelity_db = 0;
    return one_remesh;
  }());
  ASSERT_TRUE(holes.ok() && other.ok());
  auto original = catalog->FindOriginal(holes->entry.original);
  ASSERT_TRUE(original.ok() && original->has_value());
  std::ofstream(OriginalBlobPath(catalog->store_dir(), (*original)->files[0].sha256),
                std::ios::binary)
      << "OFF\n";
  ReencodeOptions options;
  options.change.precinct_coefficients = 128;
  ReencodeReport report;
  auto steps = Reencode(*catalog, options, &report);
  EXPECT_EQ(report.failed, 1u);
  EXPECT_EQ(report.reencoded, 1u);
  for (const ReencodeStep& s : steps) {
    if (s.before.id != holes->entry.id) continue;
    EXPECT_EQ(s.action, ReencodeAction::kFailed);
    EXPECT_NE(s.why.find("damaged"), std::string::npos) << s.why;
  }
  EXPECT_EQ((*catalog->Find(holes->entry.id))->sha256, holes->entry.sha256);
}

TEST_P(ReencodeTest, AReadyContainerHasNothingToBeMadeFrom) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto ingested = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(ingested.ok());
  const std::string container = ReadBytes(catalog->ContainerPath(ingested->entry));
  auto ready = IngestContainer(*catalog, container, "ready", "ready.mwv");
  ASSERT_TRUE(ready.ok()) << ready.status().ToString();
  EXPECT_TRUE(ready->entry.original.empty());
  ReencodeOptions options;
  options.change.precinct_coefficients = 128;
  ReencodeReport report;
  auto steps = Reencode(*catalog, options, &report);
  ASSERT_EQ(steps.size(), 2u);
  // Of the current format version, it is served as it is.
  EXPECT_EQ(report.reencoded, 1u);
  EXPECT_EQ(report.current, 1u);
}

INSTANTIATE_TEST_SUITE_P(Backends, ReencodeTest,
                         ::testing::Values(meshwave::testing::CatalogBackend::kSqlite,
                                           meshwave::testing::CatalogBackend::kPostgres),
                         meshwave::testing::CatalogBackendName);

}  // namespace
}  // namespace meshwave::server
