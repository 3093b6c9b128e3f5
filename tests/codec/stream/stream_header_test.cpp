// ReadStreamHeader against protobuf: the same bytes give the same fields
// (or both refuse them), on every container shipped in the repository, on
// encoder output of every coder and transform, and on hand-made wire-format
// corner cases (unknown fields, groups, unpacked repeats, merges, bad UTF-8).
#include "meshwave/stream_header.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "codec/stream/stream_header_compare_testonly.h"
#include "codec/stream/stream_test_util.h"
#include "core/protobuf_wire.h"
#include "meshwave/container.h"
#include "meshwave/encoder.h"
#include "pgc/pgc_stream.h"

namespace meshwave {
namespace {

// Both readers on `bytes`: they must agree on acceptance, every field, and
// (for bytes protobuf re-serializes the same) the bytes without `present`.
void ExpectSameAsProtobuf(std::string_view bytes, const std::string& what) {
  SCOPED_TRACE(what);
  proto::StreamHeader p;
  const bool proto_ok = p.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()));
  auto r = ReadStreamHeader(bytes);
  ASSERT_EQ(r.ok(), proto_ok) << (r.ok() ? "read, protobuf refused" : r.status().ToString());
  if (!proto_ok) return;
  EXPECT_EQ(testing::HeaderDifference(*r, p), "");
  // Through protobuf's own serialization: bytes_without_present must then
  // be exactly what protobuf writes with `present` cleared.
  auto again = ReadStreamHeader(p.SerializeAsString());
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->bytes_without_present, testing::ProtoBytesWithoutPresent(p));
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The header bytes of a container (preamble: magic, u32 length).
std::string_view HeaderBytes(std::string_view container) {
  uint32_t length = 0;
  for (int i = 3; i >= 0; --i) length = length << 8 | static_cast<uint8_t>(container[4 + i]);
  return container.substr(8, length);
}

TEST(StreamHeaderTest, ShippedContainersReadAsProtobufReadsThem) {
  // Every .mwv in the repository: test data, fuzz data and fuzz seeds
  // (seeds cut short inside the header are compared too: both refuse).
  const std::filesystem::path root = testing::TestDataDir().parent_path();
  std::set<std::string> seen;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.path().extension() != ".mwv") continue;
    const std::string bytes = ReadFile(entry.path());
    if (bytes.size() < 8) continue;  // seeds cut inside the preamble
    ExpectSameAsProtobuf(HeaderBytes(bytes), entry.path().string());
    seen.insert(entry.path().lexically_relative(root).string());
  }
  EXPECT_TRUE(seen.count("fuzz/data/octahedron_sr3.mwv") &&
              seen.count("fuzz/data/tetrahedron_sr2.mwv"));
  EXPECT_GE(seen.size(), 9u);
}

TEST(StreamHeaderTest, EncoderOutputReadsAsProtobufReadsIt) {
  struct Case {
    const char* what;
    CoderKind coder;
    Predictor predictor;
    UpdateWeights update;
  };
  for (const Case& c : {Case{"3xC butterfly", CoderKind::k3xC, Predictor::kButterfly,
                             UpdateWeights::kConstant},
                        Case{"SIM loop", CoderKind::kSim, Predictor::kLoop, UpdateWeights::kValence},
                        Case{"3xC SAWT", CoderKind::k3xC, Predictor::kSawt, UpdateWeights::kNone},
                        Case{"SIM linear", CoderKind::kSim, Predictor::kLinear,
                             UpdateWeights::kNone}}) {
    EncodeOptions options;
    options.coder = c.coder;
    options.transform.predictor = c.predictor;
    options.transform.update = c.update;
    options.sawt_alpha = 8;
    options.name = std::string("bumpy sphere \xc3\xa9 ") + c.what;
    auto s = EncodeMesh(testing::BumpySphere(3), options);
    ASSERT_TRUE(s.ok()) << c.what << ": " << s.status().ToString();
    const std::string container = SerializeFullContainer(*s);
    ExpectSameAsProtobuf(HeaderBytes(container), c.what);
    // The container's header is the encoder's bytes plus `present`.
    EXPECT_EQ(HeaderBytes(SerializeContainer(*s, {})), s->header.bytes_without_present);
  }
  auto pgc = EncodePgc(testing::BumpySphere(3), EncodeOptions{});
  ASSERT_TRUE(pgc.ok());
  ExpectSameAsProtobuf(pgc->header.bytes_without_present, "PGC");
}

// Hand-made records, for the corner cases of the wire format.
std::string Tag(uint32_t field, uint32_t wire) {
  std::string out;
  PutVarint(out, field << 3 | wire);
  return out;
}
std::string Varint(uint32_t field, uint64_t v) {
  std::string out = Tag(field, 0);
  PutVarint(out, v);
  return out;
}
std::string Delimited(uint32_t field, std::string_view bytes) {
  std::string out = Tag(field, 2);
  PutVarint(out, bytes.size());
  out += bytes;
  return out;
}
std::string Fixed64(uint32_t field, uint64_t v) {
  std::string out = Tag(field, 1);
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>(v >> (8 * i)));
  return out;
}

TEST(StreamHeaderTest, WireFormatCornerCasesMatchProtobuf) {
  const std::string quantizer = Fixed64(1, 0x3ff0000000000000) + Varint(2, 1) + Varint(3, 5);
  const std::vector<std::pair<const char*, std::string>> cases = {
      {"empty", ""},
      {"last scalar wins", Varint(1, 3) + Varint(1, 4)},
      {"uint32 keeps the low 32 bits", Varint(1, (uint64_t{7} << 32) | 9)},
      {"int32 from a negative varint", Delimited(11, Varint(3, ~uint64_t{0}))},
      {"enum value unknown to the proto", Varint(8, 77)},
      {"unknown fields of every wire type",
       Varint(99, 1) + Fixed64(100, 2) + Delimited(101, "xyz") + Tag(102, 5) + "abcd" +
           Tag(103, 3) + Varint(1, 5) + Tag(103, 4) + Varint(1, 4)},
      {"known field with another wire type is unknown", Fixed64(1, 12) + Delimited(3, "ab")},
      {"repeated unpacked", Fixed64(5, 1) + Fixed64(5, 2) + Varint(14, 3) + Varint(14, 4)},
      {"repeated packed then unpacked",
       Delimited(14, "\x01\x02") + Varint(14, 3) + Delimited(5, std::string(16, '\1'))},
      {"packed doubles not a multiple of 8", Delimited(5, std::string(12, '\1'))},
      {"packed varint running past its run", Delimited(14, "\x01\x80")},
      {"embedded messages merge",
       Delimited(7, Varint(4, 3)) + Delimited(7, Varint(1, 2)) +
           Delimited(7, Delimited(5, Varint(1, 1))) + Delimited(7, Delimited(5, Varint(2, 9)))},
      {"repeated messages append", Delimited(11, quantizer) + Delimited(11, quantizer)},
      {"valid UTF-8 name", Delimited(2, "caf\xc3\xa9 \xf0\x9f\x99\x82")},
      {"overlong UTF-8", Delimited(2, "\xc0\xaf")},
      {"surrogate in UTF-8", Delimited(2, "\xed\xa0\x80")},
      {"above U+10FFFF", Delimited(2, "\xf4\x90\x80\x80")},
      {"truncated UTF-8", Delimited(2, "\xe2\x82")},
      {"field number 0", Tag(0, 0) + "\x01"},
      {"zero tag", std::string("\x00", 1)},
      {"end group at top level", Tag(5, 4)},
      {"group without its end", Tag(50, 3) + Varint(1, 1)},
      {"group closed by another number", Tag(50, 3) + Tag(51, 4)},
      {"wire type 6", Tag(50, 6)},
      {"wire type 7", Tag(50, 7)},
      {"truncated varint", "\x08\x80"},
      // (Whole literals: GCC 12 warns wrongly on "x" + std::string(n, c).)
      {"eleven-byte varint", "\x08\x80\x80\x80\x80\x80\x80\x80\x80\x80\x80\x01"},
      {"ten-byte varint", "\x08\xff\xff\xff\xff\xff\xff\xff\xff\xff\x7f"},
      {"truncated fixed64", Tag(13, 1) + "1234"},
      {"length beyond the end", Tag(2, 2) + "\x05" + "ab"},
      {"six-byte tag", std::string("\x88\x80\x80\x80\x80\x00", 6)},
      {"five-byte tag", std::string("\x88\x80\x80\x80\x00\x01", 6)},
      {"sub-message with a zero tag", Delimited(7, std::string("\x00", 1))},
      {"present dropped from the bytes", Varint(1, 4) + Delimited(14, "\x01\x02") + Varint(9, 3)},
  };
  for (const auto& [what, bytes] : cases) ExpectSameAsProtobuf(bytes, what);
}

TEST(StreamHeaderTest, GroupsNestAsDeepAsProtobufAllows) {
  for (int depth : {99, 100, 101}) {
    std::string bytes;
    for (int i = 0; i < depth; ++i) bytes += Tag(60, 3);
    for (int i = 0; i < depth; ++i) bytes += Tag(60, 4);
    ExpectSameAsProtobuf(bytes, "groups " + std::to_string(depth) + " deep");
    ExpectSameAsProtobuf(Delimited(7, bytes), "in transform, " + std::to_string(depth) + " deep");
  }
}

TEST(StreamHeaderTest, BytesWithoutPresentDropOnlyPresent) {
  const std::string bytes = Varint(1, 4) + Delimited(14, "\x01\x02") + Varint(9, 3) + Varint(14, 7);
  auto r = ReadStreamHeader(bytes);
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->present, (std::vector<uint32_t>{1, 2, 7}));
  EXPECT_EQ(r->bytes_without_present, Varint(1, 4) + Varint(9, 3));
}

// A field added to stream.proto must be added to StreamHeader, its reader
// and HeaderDifference: this lists the field numbers all three know.
TEST(StreamHeaderTest, ProtoHasTheFieldsTheReaderKnows) {
  const auto numbers = [](const google::protobuf::Descriptor* d) {
    std::vector<int> out;
    for (int i = 0; i < d->field_count(); ++i) out.push_back(d->field(i)->number());
    std::sort(out.begin(), out.end());
    return out;
  };
  using V = std::vector<int>;
  EXPECT_EQ(numbers(proto::StreamHeader::descriptor()),
            (V{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17}));
  EXPECT_EQ(numbers(proto::Original::descriptor()), (V{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(numbers(proto::Transform::descriptor()), (V{1, 2, 3, 4, 5}));
  EXPECT_EQ(numbers(proto::SawtChoices::descriptor()), (V{1, 2, 3, 4}));
  EXPECT_EQ(numbers(proto::BaseMesh::descriptor()), (V{1, 2, 3, 4, 6, 7}));
  EXPECT_EQ(numbers(proto::Quantizer::descriptor()), (V{1, 2, 3}));
  EXPECT_EQ(numbers(proto::PacketIndex::descriptor()), (V{3, 6, 7, 8, 9, 10}));
  EXPECT_EQ(numbers(proto::Channel::descriptor()), (V{1, 2, 3, 4, 5}));
  EXPECT_EQ(numbers(proto::Texture::descriptor()), (V{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13}));
  EXPECT_EQ(numbers(proto::TextureMap::descriptor()), (V{1, 2, 3}));
  EXPECT_EQ(numbers(proto::TextureLevel::descriptor()), (V{1, 2, 3}));
}

TEST(StreamHeaderTest, RefusalSaysWhat) {
  auto r = ReadStreamHeader("\x08\x80");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kParseError);
  EXPECT_NE(r.status().message().find("stream header"), std::string::npos);
}

}  // namespace
}  // namespace meshwave
