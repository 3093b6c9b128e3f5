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
#include "mesh_identity.h"
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
  EXPECT_EQ(e.format_version, kStreamFormatVersion);
  EXPECT_EQ(e.settings, FormatEncodeSettings(EncodeChoices{}));
  // The original is kept, content-addressed, and names the mesh.
  const std::string file = ReadBytes(SampleMesh("holes.off"));
  auto original = catalog->FindOriginal(e.original);
  ASSERT_TRUE(original.ok() && original->has_value());
  EXPECT_EQ((*original)->main, "holes.off");
  ASSERT_EQ((*original)->files.size(), 1u);
  EXPECT_EQ((*original)->files[0].sha256, Sha256Hex(file));
  EXPECT_EQ(ReadBytes(OriginalBlobPath(catalog->store_dir(), Sha256Hex(file))), file);
  EXPECT_EQ(e.id, MeshIdOf(e.original, e.settings, "holes"));
  const std::string bytes = ReadBytes(catalog->ContainerPath(e));
  EXPECT_EQ(Sha256Hex(bytes), e.sha256);
  EXPECT_EQ(bytes.size(), e.bytes);
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->ids.size(), e.packets);
  EXPECT_EQ(parsed->header.vertices, e.vertices);
  EXPECT_TRUE(catalog->Find(e.id)->has_value());
}

// A remeshed mesh ingested on one thread and on three: the same container.
TEST_P(IngestTest, ThreadCountDoesNotChangeTheContainer) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  EncodeChoices one, three;
  one.threads = 1;
  three.threads = 3;
  // Under the sanitizers one remesh instead of the default fidelity's
  // repeated ones (the same parallel remesher; 48 s a backend under ASan).
  if (meshwave::testing::kUnderSanitizer) one.fidelity_db = three.fidelity_db = 0;
  auto other = Catalog::Open((tmp_ / "other").string());
  ASSERT_TRUE(other.ok());
  auto a = IngestMeshFile(*catalog, SampleMesh("elephant.off"), "", one);
  auto b = IngestMeshFile(**other, SampleMesh("elephant.off"), "", three);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(a->remeshed);
  EXPECT_FALSE(b->already_present);
  EXPECT_EQ(a->entry.sha256, b->entry.sha256);
  EXPECT_EQ(a->entry.id, b->entry.id);
  // In the same catalog, the same mesh is found without encoding it again.
  auto c = IngestMeshFile(*catalog, SampleMesh("elephant.off"), "", three);
  ASSERT_TRUE(c.ok());
  EXPECT_TRUE(c->already_present);
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
  std::thread t([&] { ra = IngestMeshBytes(*a, bytes, "h", "h.off"); });
  rb = IngestMeshBytes(*b, bytes, "h", "h.off");
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

// An .obj is ingested with the files it refers to (its .mtl, the .mtl's
// texture): the original kept is complete, so a re-encode can read it all.
// A coloured PLY keeps its colours in the container (the asset pipeline).
TEST(IngestSqliteTest, AnAssetIsKeptWithItsSidecarFilesAndItsColours) {
  TempDir tmp;
  auto catalog = Catalog::Open(tmp / "c").value();
  auto r = IngestMeshFile(*catalog, SampleMesh("textured/die.obj"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  auto original = catalog->FindOriginal(r->entry.original);
  ASSERT_TRUE(original.ok() && original->has_value());
  EXPECT_EQ((*original)->main, "die.obj");
  std::vector<std::string> names;
  for (const OriginalFile& f : (*original)->files) {
    names.push_back(f.name);
    EXPECT_EQ(ReadBytes(OriginalBlobPath(catalog->store_dir(), f.sha256)),
              ReadBytes(SampleMesh("textured/" + f.name)));
  }
  EXPECT_EQ(names, (std::vector<std::string>{"die.mtl", "die.obj", "die.png"}));

  r = IngestMeshFile(*catalog, SampleMesh("textured/hue_ball.ply"));
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  const std::string container = ReadBytes(catalog->ContainerPath(r->entry));
  auto parsed = ParseContainer(container);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(parsed->header.channels.size(), 1u);
}

TEST_P(IngestTest, RejectsMalformedMeshLeavingNothing) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshBytes(*catalog, "ply\nformat ascii 1.0\nelement vertex 99999999\n", "bad",
                           "bad.ply");
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
  // The same for originals: a blob whose row never came, and a half write.
  const auto orphan_blob = OriginalBlobPath(catalog->store_dir(), std::string(64, 'b'));
  const auto temp_blob =
      catalog->store_dir() / "originals" / (std::string(kDurableTempPrefix) + "9-0-y");
  std::ofstream(orphan_blob) << "orphan";
  std::ofstream(temp_blob) << "half";
  auto report = RemoveOrphans(*catalog);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->orphan_files, 1u);
  EXPECT_EQ(report->orphan_originals, 1u);
  EXPECT_EQ(report->temp_files, 2u);
  EXPECT_FALSE(std::filesystem::exists(orphan));
  EXPECT_FALSE(std::filesystem::exists(temp));
  EXPECT_FALSE(std::filesystem::exists(orphan_blob));
  EXPECT_FALSE(std::filesystem::exists(temp_blob));
  EXPECT_TRUE(std::filesystem::exists(catalog->ContainerPath(r->entry)));
  EXPECT_EQ(CountFilesIn(catalog->store_dir() / "originals"), 1u);
}

TEST_P(IngestTest, RemoveEntryDeletesRowThenFile) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto r = IngestMeshFile(*catalog, SampleMesh("holes.off"));
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(*RemoveEntry(*catalog, r->entry.id));
  EXPECT_FALSE(catalog->Find(r->entry.id)->has_value());
  EXPECT_FALSE(std::filesystem::exists(catalog->ContainerPath(r->entry)));
  EXPECT_EQ(CountFilesIn(catalog->store_dir() / "originals"), 0u);  // no other mesh used it
  EXPECT_FALSE(*RemoveEntry(*catalog, r->entry.id));
}

// The same upload under two names: two meshes, one original; deleting one
// keeps the original for the other.
TEST_P(IngestTest, AnOriginalSharedByTwoMeshesGoesWithTheLast) {
  auto catalog = OpenCatalog();
  ASSERT_TRUE(catalog);
  auto a = IngestMeshFile(*catalog, SampleMesh("holes.off"), "first");
  auto b = IngestMeshFile(*catalog, SampleMesh("holes.off"), "second");
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE(a->entry.id, b->entry.id);
  EXPECT_EQ(a->entry.original, b->entry.original);
  EXPECT_EQ(CountFilesIn(catalog->store_dir() / "originals"), 1u);
  EXPECT_TRUE(*RemoveEntry(*catalog, a->entry.id));
  EXPECT_EQ(CountFilesIn(catalog->store_dir() / "originals"), 1u);
  EXPECT_TRUE(catalog->FindOriginal(b->entry.original)->has_value());
  EXPECT_TRUE(*RemoveEntry(*catalog, b->entry.id));
  EXPECT_EQ(CountFilesIn(catalog->store_dir() / "originals"), 0u);
  EXPECT_FALSE(catalog->FindOriginal(b->entry.original)->has_value());
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
