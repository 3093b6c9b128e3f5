// The catalog watcher: an open mesh whose row another process swapped to a
// new container (a re-encode) or deleted is dropped, and retired, so the
// next request loads the row as it is now; open meshes that did not
// change stay.
#include "catalog_watcher.h"

#include <gtest/gtest.h>

#include "e2e/cli_runner.h"
#include "ingest.h"
#include "reencode.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

using meshwave::testing::SampleMesh;
using meshwave::testing::TempDir;

TEST(CatalogWatcherTest, DropsOpenMeshesWhoseContainerChanged) {
  TempDir tmp;
  auto catalog = Catalog::Open((tmp / "c").string());
  ASSERT_TRUE(catalog.ok());
  auto holes = IngestMeshFile(**catalog, SampleMesh("holes.off"));
  auto other = IngestMeshFile(**catalog, SampleMesh("holes.off"), "other");
  ASSERT_TRUE(holes.ok() && other.ok());
  MeshCache meshes(**catalog, 8);
  ResponseCache responses(1 << 20);
  // A long period: the test polls by hand.
  CatalogWatcher watcher(**catalog, meshes, responses, std::chrono::hours(1));
  watcher.CheckNow();
  auto before = meshes.Get(holes->entry.id);
  ASSERT_TRUE(before.ok() && *before);
  ASSERT_TRUE(meshes.Get(other->entry.id).ok());
  EXPECT_EQ(watcher.CheckNow(), 0u);  // nothing changed

  // Another process re-encodes one of them.
  auto writer = Catalog::Open((tmp / "c").string());
  ASSERT_TRUE(writer.ok());
  ReencodeOptions options;
  options.change.precinct_coefficients = 64;
  ASSERT_TRUE(ReencodeCatalog(**writer, options, nullptr).ok());
  // Both were re-encoded: both dropped and retired; the next Get serves
  // the new containers.
  EXPECT_EQ(watcher.CheckNow(), 2u);
  EXPECT_TRUE((*before)->retired());
  auto after = meshes.Get(holes->entry.id);
  ASSERT_TRUE(after.ok() && *after);
  EXPECT_NE((*after)->entry().sha256, (*before)->entry().sha256);
  EXPECT_EQ((*after)->header().packets.precinct_coefficients, 64u);
  EXPECT_EQ(watcher.CheckNow(), 0u);

  // A delete elsewhere drops it too.
  ASSERT_TRUE(*RemoveEntry(**writer, other->entry.id));
  EXPECT_EQ(watcher.CheckNow(), 0u);  // `other` was not open since the swap
  ASSERT_TRUE(meshes.Get(holes->entry.id).ok());
  ASSERT_TRUE(*RemoveEntry(**writer, holes->entry.id));
  EXPECT_EQ(watcher.CheckNow(), 1u);
  EXPECT_EQ(meshes.size(), 0u);
  EXPECT_FALSE(*meshes.Get(holes->entry.id));
}

}  // namespace
}  // namespace meshwave::server
