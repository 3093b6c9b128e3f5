// StreamCursor (server/stream_cursor.h) without a socket: what a start, a
// resume and a refine select, in packets and in units, the units it hands
// out one by one, the Done each request is owed, and the refusals that
// leave it as it was. GET /stream and the WebSocket drive it: the same
// request selects the same units over both (server_region_test and
// client region_fetch_e2e_test check that end to end).
#include "stream_cursor.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "meshwave/container.h"
#include "meshwave/region.h"
#include "sha256.h"
#include "e2e/cli_runner.h"
#include "test_data.h"

namespace meshwave::server {
namespace {

// A container with precincts and split packets (tests/fuzz/data).
std::shared_ptr<const ServedMesh> Mesh() {
  static const std::shared_ptr<const ServedMesh> mesh = [] {
    const auto path = testing::TestDataDir() / ".." / "fuzz" / "data" / "tetrahedron_sr2.mwv";
    CatalogEntry entry;
    entry.id = "0123456789ab";
    entry.sha256 = Sha256Hex(testing::ReadBytes(path));
    auto m = ServedMesh::Load(entry, path);
    EXPECT_TRUE(m.ok()) << m.status().ToString();
    return *std::move(m);
  }();
  return mesh;
}

// Everything the cursor hands out, in order.
std::vector<StreamCursor::Unit> Drain(StreamCursor& c) {
  std::vector<StreamCursor::Unit> out;
  for (auto u = c.Peek(); u; c.Advance(), u = c.Peek()) out.push_back(*u);
  return out;
}

TEST(StreamCursorTest, AStartSendsThePrefixOfTheOrderThatFitsTheBudgetWithTheHeader) {
  const auto mesh = Mesh();
  const std::vector<uint32_t>& order = mesh->Order(Progression::kRd, -1);
  ASSERT_GE(order.size(), 3u);
  const uint64_t two = ContainerSize(mesh->header(), {order.data(), 2});
  StreamRequest r;
  r.order = Progression::kRd;
  r.budget = two;
  StreamCursor c;
  auto s = c.Start(mesh, r, /*with_header=*/true);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->from, 0u);
  EXPECT_EQ(s->next, 2u);
  EXPECT_EQ(s->order_length, order.size());
  EXPECT_EQ(s->bytes, two);
  EXPECT_FALSE(s->complete);
  EXPECT_FALSE(c.DoneDue());  // two packets to send first
  const auto sent = Drain(c);
  ASSERT_EQ(sent.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(sent[k].cursor, k);
    EXPECT_EQ(sent[k].unit, StreamUnit{order[k]});
    EXPECT_EQ(sent[k].payload, mesh->payload(order[k]));
  }
  ASSERT_TRUE(c.DoneDue());
  EXPECT_EQ(c.DoneDue()->next, 2u);
  c.TakeDone();
  EXPECT_EQ(c.pending(), 0u);

  // A refine continues the order with payload bytes only.
  const uint64_t third = mesh->payload(order[2]).size();
  auto more = c.Refine(third, std::nullopt, std::nullopt);
  ASSERT_TRUE(more.ok());
  EXPECT_EQ(more->from, 2u);
  EXPECT_EQ(more->next, 3u);
  EXPECT_EQ(more->bytes, third);
  ASSERT_EQ(Drain(c).size(), 1u);
}

TEST(StreamCursorTest, AResumeCountsPayloadsFromItsCursorAndAHeaderOnlyStartSendsNone) {
  const auto mesh = Mesh();
  const std::vector<uint32_t>& order = mesh->Order(Progression::kQuality, -1);
  StreamRequest r;
  r.from = 1;
  StreamCursor c;
  auto s = c.Start(mesh, r, /*with_header=*/false);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->from, 1u);
  EXPECT_EQ(s->next, order.size());
  EXPECT_TRUE(s->complete);
  uint64_t payloads = 0;
  for (size_t k = 1; k < order.size(); ++k) payloads += mesh->payload(order[k]).size();
  EXPECT_EQ(s->bytes, payloads);
  EXPECT_EQ(Drain(c).front().cursor, 1u);

  StreamCursor h;
  auto header = h.Start(mesh, StreamRequest{}, /*with_header=*/true, /*header_only=*/true);
  ASSERT_TRUE(header.ok());
  EXPECT_EQ(header->next, 0u);
  EXPECT_EQ(header->bytes, ContainerSize(mesh->header(), {}));
  EXPECT_FALSE(h.Peek());
  EXPECT_TRUE(h.DoneDue());
}

TEST(StreamCursorTest, ARefineWithARegionCountsUnitsAndNeverSendsOneTwice) {
  const auto mesh = Mesh();
  StreamRequest r;
  r.budget = ContainerSize(mesh->header(), {mesh->Order(Progression::kQuality, -1).data(), 1});
  StreamCursor c;
  ASSERT_TRUE(c.Start(mesh, r, true).ok());
  std::vector<StreamCursor::Unit> sent = Drain(c);
  ASSERT_EQ(sent.size(), 1u);
  c.TakeDone();
  // Then the rest, a region first: units from cursor 1 on, each once.
  const Region region{SphereRegion{Vec3(0.2, 0.2, 0.2), 0.3}, std::nullopt};
  auto s = c.Refine(uint64_t{1} << 40, region, std::nullopt);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->from, 1u);
  EXPECT_TRUE(s->complete);
  for (const auto& u : Drain(c)) sent.push_back(u);
  EXPECT_EQ(sent.size(), s->order_length);
  std::set<std::pair<uint32_t, uint32_t>> seen;
  bool parts = false;
  for (size_t k = 0; k < sent.size(); ++k) {
    EXPECT_EQ(sent[k].cursor, k);
    EXPECT_TRUE(seen.insert({sent[k].unit.id, sent[k].unit.part}).second);
    parts = parts || !sent[k].unit.whole();
  }
  EXPECT_TRUE(parts);  // the fixture splits packets: a region sends parts
}

TEST(StreamCursorTest, RefusalsLeaveTheCursorAsItWas) {
  const auto mesh = Mesh();
  StreamCursor c;
  EXPECT_EQ(c.Refine(100, std::nullopt, std::nullopt).status().code(),
            StatusCode::kInvalidArgument);  // nothing started
  StreamRequest too_fine;
  too_fine.max_level = static_cast<int>(mesh->levels()) + 1;
  EXPECT_EQ(c.Start(mesh, too_fine, true).status().code(), StatusCode::kInvalidArgument);
  StreamRequest small;
  small.budget = ContainerSize(mesh->header(), {}) - 1;
  EXPECT_EQ(c.Start(mesh, small, true).status().code(), StatusCode::kInvalidArgument);
  StreamRequest past;
  past.from = mesh->Order(Progression::kQuality, -1).size() + 1;
  EXPECT_EQ(c.Start(mesh, past, false).status().code(), StatusCode::kInvalidArgument);
  StreamRequest held;
  held.held = std::string(40, '_');  // bits past the stream's last unit
  EXPECT_EQ(c.Start(mesh, held, false).status().code(), StatusCode::kInvalidArgument);
  small.region = Region{SphereRegion{Vec3::Zero(), 1}, std::nullopt};
  EXPECT_EQ(c.Start(mesh, small, true).status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(c.started());
  EXPECT_FALSE(c.Peek());
  EXPECT_EQ(c.pending(), 0u);
}

}  // namespace
}  // namespace meshwave::server
