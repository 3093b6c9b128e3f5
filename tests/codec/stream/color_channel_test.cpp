// The colour channel (format version 8): decoded colours close to the
// encoded ones at the full stream and improving along every order; the
// geometry's packets and positions untouched by it; its packets depending
// on its own only; refused with a message when its header fields do not
// fit; and version-7 streams still read.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "codec/stream/stream_header_compare_testonly.h"
#include "codec/stream/stream_test_util.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "stream.pb.h"
#include "stream/channel_base_decoder.h"
#include "stream/stream_format_writer.h"

namespace meshwave {
namespace {

// A smooth colour field with some sharper variation, in [0, 1].
std::vector<Vec3> ColorsOf(const std::vector<Vec3>& positions) {
  std::vector<Vec3> out;
  for (const Vec3& p : positions) {
    out.emplace_back(0.5 + 0.5 * std::sin(3 * p.x()), 0.5 + 0.4 * p.y(),
                     0.5 + 0.5 * std::cos(7 * p.z() + 2 * p.x()));
  }
  return out;
}

const SemiRegularMesh& Mesh() {
  static const SemiRegularMesh mesh = testing::BumpySphere(3);
  return mesh;
}

const EncodedStream& Colored() {
  static const EncodedStream stream = [] {
    VertexAttributes attributes;
    attributes.colors = ColorsOf(Mesh().positions);
    auto s = EncodeMesh(Mesh(), EncodeOptions{}, attributes);
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    return *std::move(s);
  }();
  return stream;
}

// The colour PSNR (peak 1) of a decoder holding the packets of `order`'s
// first n.
double ColorPsnr(const EncodedStream& s, const std::vector<uint32_t>& order, size_t n) {
  auto d = testing::DecoderOf(s);
  for (size_t i = 0; i < n; ++i) {
    const Status added = d->AddPacket(order[i], s.packets[order[i]]);
    EXPECT_TRUE(added.ok()) << added.ToString();
  }
  return testing::Psnr(d->Colors(), s.colors, 1.0);
}

TEST(ColorChannelTest, FullStreamGivesTheEncodedColours) {
  const EncodedStream& s = Colored();
  ASSERT_EQ(s.header.channels.size(), 1u);
  EXPECT_EQ(s.header.format_version, kStreamFormatVersion);
  ASSERT_EQ(s.colors.size(), Mesh().positions.size());
  const auto order = PacketOrder(s.header, Progression::kQuality);
  EXPECT_EQ(order.size(), s.packets.size());
  // Precision 10: steps of about 1/1000 on the finest subband.
  EXPECT_GT(ColorPsnr(s, order, order.size()), 55.0);
  // The base values alone already give the colours' broad shape.
  std::vector<Vec3> flat(s.colors.size(), Vec3::Zero());
  for (const Vec3& c : s.colors) flat[0] += c / static_cast<double>(s.colors.size());
  std::fill(flat.begin(), flat.end(), flat[0]);
  // Measured: 8.4 dB against the mean colour's 5.1 dB.
  EXPECT_GT(ColorPsnr(s, order, 0), testing::Psnr(flat, s.colors, 1.0) + 2.0);
}

TEST(ColorChannelTest, ColoursImproveAlongEveryOrder) {
  const EncodedStream& s = Colored();
  for (Progression p : {Progression::kQuality, Progression::kResolution, Progression::kRd}) {
    SCOPED_TRACE(ProgressionName(p));
    const auto order = PacketOrder(s.header, p);
    ASSERT_EQ(order.size(), s.packets.size());
    double before = ColorPsnr(s, order, 0);
    for (size_t n : {order.size() / 4, order.size() / 2, order.size()}) {
      const double now = ColorPsnr(s, order, n);
      EXPECT_GE(now, before - 0.5) << n;
      before = now;
    }
    EXPECT_GT(before, 55.0);
  }
}

TEST(ColorChannelTest, LeavesTheGeometryAlone) {
  auto plain = EncodeMesh(Mesh(), EncodeOptions{});
  ASSERT_TRUE(plain.ok());
  const EncodedStream& s = Colored();
  ASSERT_GT(s.packets.size(), plain->packets.size());
  for (size_t id = 0; id < plain->packets.size(); ++id) {
    EXPECT_EQ(s.packets[id], plain->packets[id]) << id;
    EXPECT_EQ(s.header.packets.distortion_step[id], plain->header.packets.distortion_step[id]);
  }
  // The same positions from the same geometry packets; the geometry's
  // PSNR estimate counts the geometry only.
  auto with = testing::DecoderOf(s);
  auto without = testing::DecoderOf(*plain);
  for (uint32_t id = 0; id < plain->packets.size(); ++id) {
    ASSERT_TRUE(with->AddPacket(id, s.packets[id]).ok());
    ASSERT_TRUE(without->AddPacket(id, plain->packets[id]).ok());
  }
  EXPECT_EQ(with->Positions(), without->Positions());
  EXPECT_DOUBLE_EQ(with->EstimatedPsnr(), without->EstimatedPsnr());
  EXPECT_FALSE(without->HasColors());
  EXPECT_TRUE(without->Colors().empty());
  EXPECT_TRUE(with->HasColors());
}

TEST(ColorChannelTest, ChannelPacketsNeedTheirChannelOnly) {
  const EncodedStream& s = Colored();
  auto plain = EncodeMesh(Mesh(), EncodeOptions{});
  ASSERT_TRUE(plain.ok());
  const auto first_channel_id = static_cast<uint32_t>(plain->packets.size());
  for (uint32_t id = first_channel_id; id < s.packets.size(); ++id) {
    for (uint32_t need : PacketDependencies(s.header, id)) {
      EXPECT_GE(need, first_channel_id) << id;
    }
    EXPECT_EQ(s.header.packets.length[id], s.packets[id].size());
  }
  // Colour packets alone decode (no geometry packet held).
  auto d = testing::DecoderOf(s);
  for (uint32_t id : PacketOrder(s.header, Progression::kQuality)) {
    if (id < first_channel_id) continue;
    ASSERT_TRUE(d->AddPacket(id, s.packets[id]).ok()) << id;
  }
  EXPECT_GT(testing::Psnr(d->Colors(), s.colors, 1.0), 55.0);
  EXPECT_EQ(d->Positions(0).size(), Mesh().hierarchy->vertex_count(0));
  // A coarser level's colours: one per vertex of that level.
  EXPECT_EQ(d->Colors(1).size(), Mesh().hierarchy->vertex_count(1));
}

TEST(ColorChannelTest, RdOrderPlacesColourAmongTheGeometry) {
  const EncodedStream& s = Colored();
  const auto order = PacketOrder(s.header, Progression::kRd);
  // Neither all colour first nor all colour last.
  auto plain = EncodeMesh(Mesh(), EncodeOptions{});
  ASSERT_TRUE(plain.ok());
  const size_t geometry = plain->packets.size();
  size_t first_colour = order.size(), last_geometry = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    if (order[i] >= geometry) first_colour = std::min(first_colour, i);
    if (order[i] < geometry) last_geometry = i;
  }
  EXPECT_LT(first_colour, last_geometry);
}

// The header's bytes with `edit` applied to its protobuf form.
template <class Edit>
StreamHeader Edited(const EncodedStream& s, Edit edit) {
  proto::StreamHeader p;
  EXPECT_TRUE(p.ParseFromString(s.header.bytes_without_present));
  edit(p);
  auto h = ToStreamHeader(p);
  EXPECT_TRUE(h.ok());
  return *h;
}

std::string CreateError(const StreamHeader& h) {
  auto d = ProgressiveDecoder::Create(h);
  return d.ok() ? "" : d.status().message();
}

TEST(ColorChannelTest, RefusesChannelFieldsThatDoNotFit) {
  const EncodedStream& s = Colored();
  EXPECT_EQ(CreateError(s.header), "");
  const struct {
    const char* expected;
    void (*edit)(proto::StreamHeader&);
  } cases[] = {
      {"a version-7 stream with channels (they came with version 8)",
       [](proto::StreamHeader& p) { p.set_format_version(7); }},
      {"channel 0: unknown kind 7",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->set_kind(proto::ChannelKind(7)); }},
      {"2 channels (at most 1, one of each kind)",
       [](proto::StreamHeader& p) { *p.add_channels() = p.channels(0); }},
      {"channel 0: 2 quantizers for",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->mutable_quantizers()->DeleteSubrange(2, p.channels(0).quantizers_size() - 2); }},
      {"channel 0: a quantizer is out of range",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->mutable_quantizers(1)->set_step(-1); }},
      {"channel 0: base step not finite and positive",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->set_base_step(0); }},
      {"channel 0: rd weight not finite and positive",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->set_rd_weight(NAN); }},
      {"bytes of base values for",
       [](proto::StreamHeader& p) { p.mutable_channels(0)->set_base("\x01"); }},
      {"chain distortions",
       [](proto::StreamHeader& p) { p.mutable_packets()->mutable_chain_distortion()->RemoveLast(); }},
  };
  for (const auto& c : cases) {
    const std::string error = CreateError(Edited(s, c.edit));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.expected << " / " << error;
  }
}

TEST(ColorChannelTest, BaseValuesAreCheckedAsTheyAreRead) {
  StreamHeader::Channel channel;
  channel.base_step = 0.5;
  channel.base = std::string("\x00\x01\x02\x03\x04\x05", 6);
  auto base = DecodeChannelBase(channel, 2);
  ASSERT_TRUE(base.ok()) << base.status().ToString();
  EXPECT_EQ((*base)[0], Vec3(0, -0.5, 0.5));
  EXPECT_EQ((*base)[1], Vec3(-1, 1, -1.5));
  channel.base += '\x00';
  EXPECT_NE(DecodeChannelBase(channel, 2).status().message().find("1 bytes after"),
            std::string::npos);
  channel.base = std::string(5, '\x80') + std::string("\x01\x00\x00\x00\x00\x00", 6);
  EXPECT_NE(DecodeChannelBase(channel, 2).status().message().find("longer than 5 bytes"),
            std::string::npos);
  channel.base = std::string(5, '\x00') + '\x80';
  EXPECT_NE(DecodeChannelBase(channel, 2).status().message().find("end inside value 5"),
            std::string::npos);
  channel.base = std::string(6, '\x00');
  channel.base_step = INFINITY;
  EXPECT_FALSE(DecodeChannelBase(channel, 2).ok());
}

TEST(ColorChannelTest, AVersionSevenStreamStillDecodes) {
  auto plain = EncodeMesh(Mesh(), EncodeOptions{});
  ASSERT_TRUE(plain.ok());
  EXPECT_EQ(plain->header.format_version, kStreamFormatVersion);
  EXPECT_TRUE(plain->header.channels.empty());
  EncodedStream old = *plain;
  old.header = Edited(*plain, [](proto::StreamHeader& p) { p.set_format_version(7); });
  const std::string bytes = SerializeFullContainer(old);
  auto parsed = ParseContainer(bytes);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  EXPECT_EQ(parsed->header.format_version, 7u);
  auto d = ProgressiveDecoder::Create(parsed->header);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  for (size_t i = 0; i < parsed->ids.size(); ++i) {
    ASSERT_TRUE((*d)->AddPacket(parsed->ids[i], parsed->payloads[i]).ok());
  }
  auto current = testing::DecoderOf(*plain);
  for (uint32_t id = 0; id < plain->packets.size(); ++id) {
    ASSERT_TRUE(current->AddPacket(id, plain->packets[id]).ok());
  }
  EXPECT_EQ((*d)->Positions(), current->Positions());
}

TEST(ColorChannelTest, TheReaderReadsTheChannelAsProtobufDoes) {
  const EncodedStream& s = Colored();
  proto::StreamHeader p;
  ASSERT_TRUE(p.ParseFromString(s.header.bytes_without_present));
  EXPECT_EQ(testing::HeaderDifference(s.header, p), "");
  EXPECT_EQ(s.header.channels[0].kind, StreamChannelKind::kColor);
  EXPECT_EQ(s.header.channels[0].rd_weight, 1.0f);
}

TEST(ColorChannelTest, ContainersWithAChannelParseAsProtobufParsesThem) {
  // `present` is written after the channels (FORMAT.md 1): protobuf reads
  // the same message as from its own serialization.
  const EncodedStream& s = Colored();
  const auto order = PacketOrder(s.header, Progression::kRd);
  const std::vector<uint32_t> ids(order.begin(), order.begin() + 5);
  const std::string container = SerializeContainer(s, ids);
  auto parsed = ParseContainer(container);
  ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
  EXPECT_EQ(parsed->ids, ids);
  EXPECT_EQ(parsed->header.channels.size(), 1u);
  EXPECT_EQ(ContainerSize(s.header, ids), container.size());
  proto::StreamHeader p;
  uint32_t length = 0;
  for (int i = 3; i >= 0; --i) length = length << 8 | static_cast<uint8_t>(container[4 + i]);
  ASSERT_TRUE(p.ParseFromString(container.substr(8, length)));
  EXPECT_EQ(p.present_size(), 5);
  EXPECT_EQ(p.channels_size(), 1);
}

}  // namespace
}  // namespace meshwave
