// The response cache: what PlanResponse keeps (head, merged slices), the
// bound in bytes with least-recently-used eviction, and that an entry never
// outlives its mesh's place in the MeshCache (DELETE, eviction) nor keeps
// the mesh alive.
#include "response_cache.h"

#include <gtest/gtest.h>

#include "catalog.h"
#include "e2e/cli_runner.h"
#include "ingest.h"
#include "mesh_cache.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

using meshwave::testing::SampleMesh;
using meshwave::testing::TempDir;

class ResponseCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto catalog = Catalog::Open((dir_ / "catalog").string(), {});
    ASSERT_TRUE(catalog.ok()) << catalog.status().ToString();
    catalog_ = std::move(*catalog);
    auto ingested = IngestMeshFile(*catalog_, SampleMesh("holes.off"));
    ASSERT_TRUE(ingested.ok()) << ingested.status().ToString();
    id_ = ingested->entry.id;
    meshes_ = std::make_unique<MeshCache>(*catalog_, 4);
    auto mesh = meshes_->Get(id_);
    ASSERT_TRUE(mesh.ok() && *mesh);
    mesh_ = *mesh;
  }

  // A 200 whose body is `count` slices of 10 bytes of the container, every
  // other one skipped (so none are adjacent).
  Response PacketLike(size_t count) const {
    Response r{http::status::ok, 11};
    r.set(http::field::content_type, "application/octet-stream");
    r.set(http::field::etag, "\"tag\"");
    r.body().mesh = mesh_;
    const std::string_view bytes = mesh_->map()->bytes();
    for (size_t i = 0; i < count; ++i) r.body().AddSlice(bytes.substr(20 * i, 10));
    return r;
  }

  TempDir dir_;
  std::unique_ptr<Catalog> catalog_;
  std::unique_ptr<MeshCache> meshes_;
  std::string id_;
  std::shared_ptr<const ServedMesh> mesh_;
};

TEST_F(ResponseCacheTest, PlanKeepsTheHeadAndMergesAdjacentSlices) {
  Response r{http::status::partial_content, 11};
  r.set(http::field::content_range, "bytes 0-34/99");
  r.body().mesh = mesh_;
  r.body().owned = "prefix";
  const std::string_view bytes = mesh_->map()->bytes();
  r.body().AddSlice(bytes.substr(0, 10));
  r.body().AddSlice(bytes.substr(10, 10));  // follows the first: merged
  r.body().AddSlice(bytes.substr(30, 5));
  const auto c = PlanResponse(std::move(r));
  EXPECT_EQ(c->status, 206u);
  EXPECT_EQ(c->body_bytes, 6u + 25u);
  EXPECT_EQ(c->owned, "prefix");
  ASSERT_EQ(c->slices.size(), 2u);
  EXPECT_EQ(c->slices[0].data(), bytes.data());
  EXPECT_EQ(c->slices[0].size(), 20u);
  EXPECT_EQ(c->slices[1].data(), bytes.data() + 30);
  EXPECT_EQ(c->slices[1].size(), 5u);
  EXPECT_EQ(c->head,
            "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 0-34/99\r\n"
            "Server: meshwave\r\nContent-Length: 31\r\n\r\n");
  EXPECT_EQ(c->fields(),
            "Content-Range: bytes 0-34/99\r\nServer: meshwave\r\nContent-Length: 31\r\n");
  EXPECT_EQ(c->mesh.lock(), mesh_);
}

TEST_F(ResponseCacheTest, GetReturnsWhatPutKeptWithItsMesh) {
  ResponseCache cache(1 << 20);
  EXPECT_FALSE(cache.Get("/a").response);
  const auto planned = PlanResponse(PacketLike(3));
  cache.Put("/a", planned);
  const ResponseCache::Hit hit = cache.Get("/a");
  EXPECT_EQ(hit.response, planned);
  EXPECT_EQ(hit.mesh, mesh_);
  EXPECT_FALSE(cache.Get("/b").response);
  EXPECT_EQ(cache.hits(), 1u);
  EXPECT_EQ(cache.misses(), 2u);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_GE(cache.bytes(), planned->charge());
}

TEST_F(ResponseCacheTest, StaysWithinItsBoundEvictingTheLeastRecentlyUsed) {
  const uint64_t charge = PlanResponse(PacketLike(8))->charge() + 2 * 2;  // keys "/0".."/9"
  ResponseCache cache(3 * charge + charge / 2);  // room for three
  cache.Put("/0", PlanResponse(PacketLike(8)));
  cache.Put("/1", PlanResponse(PacketLike(8)));
  cache.Put("/2", PlanResponse(PacketLike(8)));
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_TRUE(cache.Get("/0").response);  // now the most recent
  cache.Put("/3", PlanResponse(PacketLike(8)));
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_LE(cache.bytes(), 3 * charge + charge / 2);
  EXPECT_FALSE(cache.Get("/1").response) << "the least recently used goes first";
  EXPECT_TRUE(cache.Get("/0").response);
  EXPECT_TRUE(cache.Get("/2").response);
  EXPECT_TRUE(cache.Get("/3").response);
  // The same key again replaces, not adds.
  cache.Put("/3", PlanResponse(PacketLike(8)));
  EXPECT_EQ(cache.size(), 3u);
}

TEST_F(ResponseCacheTest, KeepsNothingLargerThanTheBoundOrWhenOff) {
  const auto big = PlanResponse(PacketLike(64));
  ResponseCache small(big->charge() / 2);
  small.Put("/big", big);
  EXPECT_EQ(small.size(), 0u);
  EXPECT_EQ(small.bytes(), 0u);
  ResponseCache off(0);
  EXPECT_FALSE(off.enabled());
  off.Put("/a", PlanResponse(PacketLike(1)));
  EXPECT_FALSE(off.Get("/a").response);
  EXPECT_EQ(off.size(), 0u);
}

TEST_F(ResponseCacheTest, DeletedMeshIsNeverServedAgain) {
  ResponseCache cache(1 << 20);
  cache.Put("/a", PlanResponse(PacketLike(2)));
  cache.Put("/b", PlanResponse(PacketLike(2)));
  // What DeleteMesh does: the MeshCache forgets (and retires) the mesh,
  // then the response cache drops its entries. A response in flight still
  // holds the mesh: retirement, not the mesh's death, is what counts.
  meshes_->Evict(id_);
  EXPECT_TRUE(mesh_->retired());
  EXPECT_FALSE(cache.Get("/a").response);
  cache.EraseRetired();
  EXPECT_EQ(cache.size(), 0u);
  EXPECT_EQ(cache.bytes(), 0u);
  // A response planned before the DELETE and put after it is not kept.
  cache.Put("/c", PlanResponse(PacketLike(2)));
  EXPECT_EQ(cache.size(), 0u);
  // The mesh loaded anew is served, and cached, again.
  auto fresh = meshes_->Get(id_);
  ASSERT_TRUE(fresh.ok() && *fresh);
  EXPECT_FALSE((*fresh)->retired());
  mesh_ = *fresh;
  cache.Put("/a", PlanResponse(PacketLike(2)));
  EXPECT_EQ(cache.Get("/a").mesh, *fresh);
}

TEST_F(ResponseCacheTest, EntriesHoldTheirMeshWeakly) {
  ResponseCache cache(1 << 20);
  cache.Put("/a", PlanResponse(PacketLike(2)));
  std::weak_ptr<const ServedMesh> watch = mesh_;
  // Evicted from the MeshCache by other meshes (here: by hand) and no
  // response in flight: the mesh and its memory map are freed although the
  // response cache still lists an entry.
  meshes_->Evict(id_);
  mesh_.reset();
  EXPECT_TRUE(watch.expired());
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_FALSE(cache.Get("/a").response);
  EXPECT_EQ(cache.size(), 0u);
}

}  // namespace
}  // namespace meshwave::server
