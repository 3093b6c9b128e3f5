// Atomic ingest, against both catalog backends: content-addressed
// containers, idempotence (also between two handles racing, as two
// replicas would), orphan and temporary file cleanup, deletion, and
// refusals that leave nothing behind.
#include "ingest.h"

#include <gtest/gtest.h>

#include <fstream>
#include <thread>

#include "core/durable_file.h"
#include "e2e/cli_runner.h"
#include "meshwave/container.h"
#include "meshwave/mesh_io.h"
#include "server/catalog_backends_testonly.h"
#include "sha256.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

using meshwave::testing::CatalogBackend;
using meshwave::testing::CatalogBackendTest;
using meshwave::testing::CountFilesIn;
using meshwave::testing::ReadBytes;
using meshwave::testing::SampleMesh;
using meshwave::testing::TempDir;

using IngestTest = CatalogBackendTest;

TEST_P(IngestTest, StoresAContentAddressedContainer) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_FALSE(r->already_present);
  EXPECT_FALSE(r->remeshed);
  const CatalogEntry& e = r->entry;
  EXPECT_EQ(e.name, "holes");
  EXPECT_EQ(e.source, "holes.off");
  EXPECT_EQ(e.container, "containers/" + e.sha256 + ".mwv");
  EXPECT_EQ(e.id, e.sha256.substr(0, 12));
  const std::string bytes = ReadBytes(catalog->ContainerPath(e));
  EXPECT_EQ(Sha256Hex(bytes), e.sha256);
  EXPECT_EQ(bytes.size(), e.bytes);
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->ids.size(), e.packets);
  EXPECT_EQ(parsed->header.vertices, e.vertices);
  EXPECT_TRUE(catalog->Find(e.id)->has_value());
}

// A remeshed mesh ingested on one thread and on three: the same container,
// so the second finds the first's entry.
TEST_P(IngestTest, ThreadCountDoesNotChangeTheContainer) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  EncodeChoices one, three;
  one.threads = 1;
  three.threads = 3;
  // Under the sanitizers one remesh instead of the default fidelity's
  // repeated ones (the same parallel remesher; 48 s a backend under ASan).
  if (meshwave::testing::kUnderSanitizer) one.fidelity_db = three.fidelity_db = 0;
  auto a = IngestMeshFile(*catalog, SampleMesh("elephant.off"), "", one);
  auto b = IngestMeshFile(*catalog, SampleMesh("elephant.off"), "", three);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(a->remeshed);
  EXPECT_FALSE(a->already_present);
  EXPECT_TRUE(b->already_present);
  EXPECT_EQ(a->entry.sha256, b->entry.sha256);
}

TEST_P(IngestTest, SameFileTwiceGivesTheSameEntry) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto a = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  auto b = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(b->already_present);
  EXPECT_EQ(a->entry.id, b->entry.id);
  EXPECT_EQ(*catalog->Count(), 1u);
  EXPECT_EQ(CountFilesIn(catalog->containers_dir()), 1u);
}

TEST_P(IngestTest, TwoHandlesIngestingTheSameMeshAtOnceMakeOneEntry) {
  auto a = OpenCatalog();
  auto b = OpenCatalog();
  ASSERT_TRUE(a && b);
  const std::string bytes = ReadBytes(SampleMesh("holes.off"));
  Result<IngestResult> ra = Status(StatusCode::kInternal, "not run");
  Result<IngestResult> rb = ra;
  std::thread t([&] { ra = IngestMeshBytes(*a, bytes, MeshFormat::kOff, "h", "h.off"); });
  rb = IngestMeshBytes(*b, bytes, MeshFormat::kOff, "h", "h.off");
  t.join();
  ASSERT_TRUE(ra.ok()) << ra.status().ToString();
  ASSERT_TRUE(rb.ok()) << rb.status().ToString();
  EXPECT_EQ(ra->entry.id, rb->entry.id);
  EXPECT_NE(ra->already_present, rb->already_present);  // exactly one wrote it
  EXPECT_EQ(*a->Count(), 1u);
  EXPECT_EQ(CountFilesIn(a->containers_dir()), 1u);
}

TEST(IngestSqliteTest, RemeshesIrregularInput) {
  TempDir tmp;
  auto catalog = Catalog::Open(tmp / "c").value();
  auto r = IngestMeshFile(*catalog, meshwave::testing::SampleMesh("elephant.off"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_TRUE(r->remeshed);
  EXPECT_GE(r->entry.levels, 1u);
}

TEST_P(IngestTest, RejectsMalformedMeshLeavingNothing) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshBytes(*catalog, "ply\nformat ascii 1.0\nelement vertex 99999999\n",
                           MeshFormat::kPly, "bad", "bad.ply");
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(*catalog->Count(), 0u);
  EXPECT_EQ(CountFilesIn(catalog->containers_dir()), 0u);
  EXPECT_FALSE(IngestContainer(*catalog, "MWV1 not a container", "x", "x.mwv").ok());
  EXPECT_EQ(CountFilesIn(catalog->containers_dir()), 0u);
}

TEST_P(IngestTest, RemovesOrphanAndTemporaryFiles) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(r.ok());
  // A container renamed into place but never committed, and a half write.
  const auto orphan = catalog->containers_dir() / (std::string(64, 'a') + ".mwv");
  const auto temp = catalog->containers_dir() / (std::string(kDurableTempPrefix) + "123-0-x.mwv");
  std::ofstream(orphan) << "orphan";
  std::ofstream(temp) << "half";
  auto report = RemoveOrphans(*catalog);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->orphan_files, 1u);
  EXPECT_EQ(report->temp_files, 1u);
  EXPECT_FALSE(std::filesystem::exists(orphan));
  EXPECT_FALSE(std::filesystem::exists(temp));
  EXPECT_TRUE(std::filesystem::exists(catalog->ContainerPath(r->entry)));
}

TEST_P(IngestTest, RemoveEntryDeletesRowThenFile) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(*RemoveEntry(*catalog, r->entry.id));
  EXPECT_FALSE(catalog->Find(r->entry.id)->has_value());
  EXPECT_FALSE(std::filesystem::exists(catalog->ContainerPath(r->entry)));
  EXPECT_FALSE(*RemoveEntry(*catalog, r->entry.id));
}

INSTANTIATE_TEST_SUITE_P(Backends, IngestTest,
                         ::testing::Values(CatalogBackend::kSqlite, CatalogBackend::kPostgres),
                         meshwave::testing::CatalogBackendName);

TEST(Sha256Test, MatchesKnownDigest) {
  EXPECT_EQ(Sha256Hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

}  // namespace
}  // namespace meshwave::server
