// The units' wire forms (meshwave/stream_units.h): numbering, the held
// bitmap (round trip, refusals, closure) and unit records read from a body
// cut anywhere.
#include "meshwave/region_order.h"
#include "meshwave/stream_units.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "codec/stream/precinct_stream_testonly.h"
#include "core/base64.h"
#include "meshwave/progression.h"

namespace meshwave {
namespace {

using testing::Precincted;

struct Units {
  explicit Units(StreamPrecincts p)
      : precincts(std::move(p)), empty(Precincted().header, precincts.parents()), numbering(empty) {}
  StreamPrecincts precincts;
  HeldUnits empty;
  UnitNumbering numbering;
};

const Units& TheUnits() {
  static const Units* u = [] {
    auto precincts = StreamPrecincts::Create(Precincted().header);
    EXPECT_TRUE(precincts.ok()) << precincts.status().ToString();
    return new Units(*std::move(precincts));
  }();
  return *u;
}

// The units in a random order that respects their dependencies.
std::vector<StreamUnit> RandomUnitOrder(uint32_t seed) {
  const Units& u = TheUnits();
  HeldUnits held = u.empty;
  std::mt19937 rng(seed);
  std::vector<StreamUnit> order;
  while (order.size() < u.numbering.size()) {
    std::vector<StreamUnit> ready;
    for (size_t n = 0; n < u.numbering.size(); ++n) {
      if (held.Ready(u.numbering.unit(n))) ready.push_back(u.numbering.unit(n));
    }
    if (ready.empty()) break;
    const StreamUnit next = ready[rng() % ready.size()];
    held.Add(next);
    order.push_back(next);
  }
  return order;
}

TEST(StreamUnitsTest, NumberingCoversEveryPartAndUnsplitPacketOnce) {
  const Units& u = TheUnits();
  size_t split = 0, expected = 0;
  for (uint32_t id = 0; id < u.empty.packet_count(); ++id) {
    const uint32_t parts = u.empty.PartCount(id);
    split += parts > 0;
    expected += parts > 0 ? parts : 1;
  }
  ASSERT_GT(split, 0u);
  ASSERT_EQ(u.numbering.size(), expected);
  for (size_t n = 0; n < u.numbering.size(); ++n) {
    EXPECT_EQ(u.numbering.number(u.numbering.unit(n)), n);
    EXPECT_TRUE(u.empty.Valid(u.numbering.unit(n)));
  }
  EXPECT_EQ(RandomUnitOrder(1).size(), u.numbering.size());
}

TEST(StreamUnitsTest, HeldBitmapRoundTripsAlongARandomOrder) {
  const Units& u = TheUnits();
  const std::vector<StreamUnit> order = RandomUnitOrder(7);
  HeldUnits held = u.empty;
  EXPECT_EQ(EncodeHeldUnits(held, u.numbering), "");
  for (size_t k = 0; k < order.size(); ++k) {
    held.Add(order[k]);
    if (k % 17 != 0 && k + 1 != order.size()) continue;
    const std::string text = EncodeHeldUnits(held, u.numbering);
    EXPECT_LE(text.size(), (u.numbering.size() + 5) / 6);
    HeldUnits back = u.empty;
    ASSERT_TRUE(DecodeHeldUnits(text, u.numbering, back).ok()) << k;
    for (size_t n = 0; n < u.numbering.size(); ++n) {
      ASSERT_EQ(back.Has(u.numbering.unit(n)), held.Has(u.numbering.unit(n))) << k << " " << n;
    }
  }
}

TEST(StreamUnitsTest, HeldBitmapRefusesGarbageBitsPastTheEndAndUnclosedSets) {
  const Units& u = TheUnits();
  HeldUnits held = u.empty;
  EXPECT_FALSE(DecodeHeldUnits("a+b", u.numbering, held).ok());
  // A bit past the last unit, in the last byte or beyond it.
  std::string bitmap((u.numbering.size() + 7) / 8 + 1, '\0');
  bitmap.back() = 1;
  auto s = DecodeHeldUnits(Base64Url(bitmap), u.numbering, held);
  EXPECT_FALSE(s.ok());
  // The last unit alone: it needs the ones before it.
  const size_t last = u.numbering.size() - 1;
  std::string one(last / 8 + 1, '\0');
  one[last / 8] = static_cast<char>(1u << (last % 8));
  held = u.empty;
  s = DecodeHeldUnits(Base64Url(one), u.numbering, held);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("without a unit it depends on"), std::string::npos) << s.message();
}

// The bitmap's length and padding (docs/API.md, "Units and the held
// bitmap"): at most ceil(N / 8) bytes for N units, shorter where the
// trailing bytes are zero, never longer even with zeros; base64url
// without '=' padding, the last digit's unused bits zero.
TEST(StreamUnitsTest, HeldBitmapIsAtMostCeilNOver8BytesUnpadded) {
  const Units& u = TheUnits();
  const size_t bytes = (u.numbering.size() + 7) / 8;
  ASSERT_GE(bytes, 3u);
  // The first unit held (it needs nothing), written at every length.
  for (size_t length = 1; length <= bytes; ++length) {
    std::string bitmap(length, '\0');
    bitmap[0] = 1;
    HeldUnits held = u.empty;
    ASSERT_TRUE(DecodeHeldUnits(Base64Url(bitmap), u.numbering, held).ok()) << length;
    EXPECT_TRUE(held.Has(u.numbering.unit(0)));
    EXPECT_EQ(EncodeHeldUnits(held, u.numbering), "AQ");  // trailing zeros left out
  }
  std::string longer(bytes + 1, '\0');
  longer[0] = 1;
  HeldUnits held = u.empty;
  const Status s = DecodeHeldUnits(Base64Url(longer), u.numbering, held);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("bytes of bitmap for a stream of"), std::string::npos) << s.message();
  held = u.empty;
  EXPECT_EQ(DecodeHeldUnits("AQ==", u.numbering, held).code(), StatusCode::kInvalidArgument);
  held = u.empty;
  EXPECT_EQ(DecodeHeldUnits("AR", u.numbering, held).code(), StatusCode::kInvalidArgument);
  held = u.empty;
  EXPECT_EQ(DecodeHeldUnits("A", u.numbering, held).code(), StatusCode::kInvalidArgument);
}

TEST(StreamUnitsTest, RecordsReadBackWhereverTheBodyIsCut) {
  const EncodedStream& s = Precincted();
  const Units& u = TheUnits();
  std::string body;
  std::vector<std::pair<StreamUnit, std::string>> sent;
  for (size_t n = 0; n < u.numbering.size(); n += 3) {
    const StreamUnit unit = u.numbering.unit(n);
    const std::string payload = s.packets[unit.id].substr(0, 1 + n % 300);
    AppendUnitRecord(body, unit, payload);
    sent.emplace_back(unit, payload);
  }
  for (size_t piece : {size_t{1}, size_t{2}, size_t{7}, size_t{1000}, body.size()}) {
    std::vector<std::pair<StreamUnit, std::string>> got;
    UnitRecordReader reader(1 << 20, [&](StreamUnit unit, std::string_view payload) {
      got.emplace_back(unit, std::string(payload));
      return Status::Ok();
    });
    for (size_t at = 0; at < body.size(); at += piece) {
      ASSERT_TRUE(reader.Feed(std::string_view(body).substr(at, piece)).ok());
    }
    EXPECT_TRUE(reader.at_boundary());
    EXPECT_EQ(got, sent) << piece;
  }
  // Cut inside the last record: not at a boundary.
  UnitRecordReader reader(1 << 20, [](StreamUnit, std::string_view) { return Status::Ok(); });
  ASSERT_TRUE(reader.Feed(std::string_view(body).substr(0, body.size() - 1)).ok());
  EXPECT_FALSE(reader.at_boundary());
  EXPECT_EQ(reader.records(), sent.size() - 1);
}

TEST(StreamUnitsTest, RecordReaderRefusesLongPayloadsAndVarintsAndStopsOnTheHandlersError) {
  std::string body;
  AppendUnitRecord(body, {3, 1}, std::string(100, 'x'));
  UnitRecordReader small(99, [](StreamUnit, std::string_view) { return Status::Ok(); });
  EXPECT_EQ(small.Feed(body).code(), StatusCode::kParseError);
  UnitRecordReader varint(1000, [](StreamUnit, std::string_view) { return Status::Ok(); });
  EXPECT_EQ(varint.Feed(std::string(6, '\xff')).code(), StatusCode::kParseError);
  UnitRecordReader refusing(1000, [](StreamUnit u, std::string_view) {
    return u.part == 1 ? InvalidArgument("no") : Status::Ok();
  });
  EXPECT_EQ(refusing.Feed(body).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace meshwave
