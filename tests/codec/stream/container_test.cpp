#include "meshwave/container.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <random>

#include "codec/stream/stream_test_util.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "stream/stream_format_writer.h"

namespace meshwave {
namespace {

const EncodedStream& Stream() {
  static const EncodedStream s = [] {
    auto r = EncodeMesh(testing::BumpySphere(3), EncodeOptions{});
    EXPECT_TRUE(r.ok());
    return *std::move(r);
  }();
  return s;
}

// Parses and decodes whatever a container holds; never crashes.
Status DecodeAll(std::string_view bytes, bool allow_truncated) {
  MW_ASSIGN_OR_RETURN(ParsedContainer c, ParseContainer(bytes, allow_truncated));
  MW_ASSIGN_OR_RETURN(auto d, ProgressiveDecoder::Create(c.header));
  for (size_t i = 0; i < c.ids.size(); ++i) {
    MW_RETURN_IF_ERROR(d->AddPacket(c.ids[i], c.payloads[i]));
  }
  (void)d->Positions();
  return Status::Ok();
}

TEST(ContainerTest, FullContainerRoundTrips) {
  const std::string bytes = SerializeFullContainer(Stream());
  auto c = ParseContainer(bytes);
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  ASSERT_EQ(c->ids.size(), Stream().packets.size());
  for (size_t i = 0; i < c->ids.size(); ++i) {
    EXPECT_EQ(c->payloads[i], Stream().packets[c->ids[i]]);
  }
  EXPECT_TRUE(DecodeAll(bytes, false).ok());
}

TEST(ContainerTest, SizeMatchesSerialization) {
  const auto order = PacketOrder(Stream().header, Progression::kQuality);
  for (size_t n = 0; n <= order.size(); n += 3) {
    std::vector<uint32_t> ids(order.begin(), order.begin() + static_cast<long>(n));
    EXPECT_EQ(ContainerSize(Stream().header, ids), SerializeContainer(Stream(), ids).size());
  }
  // A header that already lists packets (as a parsed container's does):
  // its own list does not count, the one asked about does.
  const std::vector<uint32_t> held(order.begin(), order.begin() + static_cast<long>(order.size() / 2));
  const std::string partial = SerializeContainer(Stream(), held);
  auto parsed = ParseContainer(partial);
  ASSERT_TRUE(parsed.ok());
  EXPECT_EQ(ContainerSize(parsed->header, held), partial.size());
  EXPECT_EQ(ContainerSize(parsed->header, {}), SerializeContainer(Stream(), {}).size());
  EXPECT_EQ(ContainerSize(parsed->header, order), SerializeFullContainer(Stream()).size());
}

TEST(ContainerTest, HeadFromCachedHeaderBytesIsWhatProtobufWrites) {
  // The head built by appending `present` to bytes serialized once must be
  // byte for byte protobuf's own serialization (ETags and CRC-free clients
  // compare bytes).
  proto::StreamHeader header;
  ASSERT_TRUE(header.ParseFromString(Stream().header.bytes_without_present));
  const std::string cached = header.SerializeAsString();
  EXPECT_EQ(cached, Stream().header.bytes_without_present);
  const auto order = PacketOrder(Stream().header, Progression::kRd);
  for (size_t n : {size_t{0}, size_t{1}, order.size() / 2, order.size()}) {
    const std::vector<uint32_t> ids(order.begin(), order.begin() + static_cast<long>(n));
    proto::StreamHeader with = header;
    for (uint32_t id : ids) with.add_present(id);
    const std::string body = with.SerializeAsString();
    std::string expected = "MWV1";
    for (int i = 0; i < 4; ++i) expected.push_back(static_cast<char>((body.size() >> (8 * i)) & 0xff));
    expected += body;
    EXPECT_EQ(SerializeContainerHead(cached, ids), expected) << n;
    EXPECT_EQ(SerializeContainerHead(Stream().header, ids), expected) << n;
  }
}

TEST(ContainerTest, BudgetSelectsLongestFittingPrefix) {
  const auto& h = Stream().header;
  const auto order = PacketOrder(h, Progression::kQuality);
  for (uint64_t budget : {100u, 500u, 2000u, 8000u, 1u << 30}) {
    const Selection s = SelectPackets(h, order, budget);
    if (s.ids.empty() && ContainerSize(h, {}) > budget) continue;
    EXPECT_LE(SerializeContainer(Stream(), s.ids).size(), budget);
    EXPECT_EQ(s.bytes, SerializeContainer(Stream(), s.ids).size());
    if (s.next_cursor < order.size()) {
      auto more = s.ids;
      more.push_back(order[s.next_cursor]);
      EXPECT_GT(ContainerSize(h, more), budget);
    }
    EXPECT_TRUE(DecodeAll(SerializeContainer(Stream(), s.ids), false).ok());
    // Continuing from the cursor with a payload budget.
    const Selection more = SelectPackets(h, order, 1000, s.next_cursor);
    EXPECT_LE(more.bytes, 1000u);
  }
}

TEST(ContainerTest, RejectsBadMagicVersionTrailingBytes) {
  std::string bytes = SerializeFullContainer(Stream());
  std::string bad = bytes;
  bad[0] = 'X';
  EXPECT_NE(ParseContainer(bad).status().message().find("magic"), std::string::npos);
  const std::string trailing = bytes + "zz";
  EXPECT_NE(ParseContainer(trailing).status().message().find("after the last packet"),
            std::string::npos);
  // The old base code, the version before the SAWT field, the one before the
  // compact packet index, the one before the base refinement, the one before
  // 3xC's neighbour contexts, and a future one.
  for (uint32_t version : {1u, 2u, 3u, 4u, 5u, kStreamFormatVersion + 1}) {
    EncodedStream other = Stream();
    proto::StreamHeader p;
    ASSERT_TRUE(p.ParseFromString(other.header.bytes_without_present));
    p.set_format_version(version);
    other.header = *ToStreamHeader(p);
    const std::string versioned = SerializeFullContainer(other);
    EXPECT_EQ(ParseContainer(versioned).status().code(),
              StatusCode::kUnsupported);
  }
  EXPECT_FALSE(ParseContainer("MWV1").ok());
}

// Version 6 is version 7 without precincts, read as such (a catalog of the
// previous release is served while it is re-encoded); one with precincts
// is no version-6 stream.
TEST(ContainerTest, ReadsVersionSixWithoutPrecincts) {
  for (uint32_t precincts : {0u, 8u}) {
    EncodeOptions options;
    options.precinct_coefficients = precincts;
    auto encoded = EncodeMesh(testing::BumpySphere(3), options);
    ASSERT_TRUE(encoded.ok());
    EncodedStream stream = *std::move(encoded);
    proto::StreamHeader p;
    ASSERT_TRUE(p.ParseFromString(stream.header.bytes_without_present));
    p.set_format_version(6);
    stream.header = *ToStreamHeader(p);
    const std::string bytes = SerializeFullContainer(stream);
    auto parsed = ParseContainer(bytes);
    if (precincts == 0) {
      ASSERT_TRUE(parsed.ok()) << parsed.status().ToString();
      EXPECT_EQ(parsed->header.format_version, 6u);
      EXPECT_TRUE(DecodeAll(bytes, false).ok());
    } else {
      EXPECT_EQ(parsed.status().code(), StatusCode::kParseError);
      EXPECT_NE(parsed.status().message().find("version-6 stream with precincts"),
                std::string::npos);
    }
  }
}

TEST(ContainerTest, PreambleGivesTheLittleEndianHeaderLength) {
  const std::string bytes = SerializeFullContainer(Stream());
  const Result<uint32_t> length = ReadContainerHeaderLength(bytes);
  ASSERT_TRUE(length.ok()) << length.status().ToString();
  // The header's protobuf bytes follow the preamble and end where it says.
  proto::StreamHeader p;
  EXPECT_TRUE(p.ParseFromString(bytes.substr(kContainerPreambleBytes, *length)));
  size_t payloads = 0;
  for (const std::string& packet : Stream().packets) payloads += packet.size();
  EXPECT_EQ(*length, bytes.size() - kContainerPreambleBytes - payloads);
  // Byte order: 0x04030201, not checked against the 64 MiB limit here.
  EXPECT_EQ(*ReadContainerHeaderLength(std::string("MWV1\x01\x02\x03\x04", 8)), 0x04030201u);
  EXPECT_EQ(*ReadContainerHeaderLength(std::string("MWV1\xff\xff\xff\xff", 8)), 0xffffffffu);
  EXPECT_NE(ParseContainer(std::string_view("MWV1\xff\xff\xff\xff", 8)).status().message().find(
                "exceeds the limit"),
            std::string::npos);
  EXPECT_EQ(ReadContainerHeaderLength("MWV1\x01\x02").status().code(), StatusCode::kParseError);
  EXPECT_NE(ReadContainerHeaderLength(std::string("MWV2\0\0\0\0", 8)).status().message().find(
                "wrong magic"),
            std::string::npos);
}

TEST(ContainerTest, EveryTruncationIsRefusedOrDecodesAPrefix) {
  const std::string bytes = SerializeFullContainer(Stream());
  for (size_t n = 0; n < bytes.size(); n += 7) {
    // Each prefix in its own allocation so that ASan sees any overrun.
    auto copy = std::make_unique<char[]>(n + 1);
    std::memcpy(copy.get(), bytes.data(), n);
    const std::string_view prefix(copy.get(), n);
    EXPECT_FALSE(ParseContainer(prefix, false).ok()) << n;
    auto c = ParseContainer(prefix, true);
    if (c.ok()) {
      EXPECT_TRUE(DecodeAll(prefix, true).ok()) << n;
    }
  }
}

TEST(ContainerTest, FlippedAndShuffledBytesNeverCrash) {
  const std::string bytes = SerializeFullContainer(Stream());
  std::mt19937 rng(11);
  int decoded = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string bad = bytes;
    const int flips = 1 + static_cast<int>(rng() % 4);
    for (int i = 0; i < flips; ++i) bad[rng() % bad.size()] ^= static_cast<char>(1 + rng() % 255);
    if (trial % 3 == 0) {
      const size_t a = rng() % bad.size(), b = rng() % bad.size();
      std::swap(bad[a], bad[b]);
    }
    decoded += DecodeAll(bad, true).ok();
  }
  // Most damage lands in payloads and is caught by the CRC.
  EXPECT_LT(decoded, 300);
}

}  // namespace
}  // namespace meshwave
