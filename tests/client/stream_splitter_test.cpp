#include "stream_splitter.h"

#include <gtest/gtest.h>

#include "client_test_stream.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"

namespace meshwave::client {
namespace {

using testing::ClientTestStream;

constexpr uint64_t kNoLimit = uint64_t{64} << 20;

// Collects the packets of the quality order.
class Collector : public StreamSplitter::Events {
 public:
  Status OnHeader(const StreamHeader& h) override {
    header = h;
    order = PacketOrder(h, Progression::kQuality);
    return Status::Ok();
  }
  std::optional<uint64_t> NextPacketLength() override {
    if (payloads.size() >= expected) return std::nullopt;
    return PacketLength(header, order[payloads.size()]);
  }
  Status OnPacket(std::string_view p) override {
    payloads.emplace_back(p);
    return Status::Ok();
  }
  StreamHeader header;
  std::vector<uint32_t> order;
  std::vector<std::string> payloads;
  size_t expected = 0;
};

TEST(StreamSplitterTest, SplitsAContainerFedInPiecesOfAnySize) {
  const auto& s = ClientTestStream();
  const auto order = PacketOrder(s.header, Progression::kQuality);
  const std::vector<uint32_t> ids(order.begin(), order.begin() + 10);
  const std::string body = SerializeContainer(s, ids);
  for (size_t piece : {1u, 3u, 100u, 100000u}) {
    Collector c;
    c.expected = ids.size();
    StreamSplitter splitter(true, kNoLimit, c);
    for (size_t pos = 0; pos < body.size(); pos += piece) {
      ASSERT_TRUE(
          splitter.Feed(std::string_view(body).substr(pos, piece)).ok());
    }
    EXPECT_TRUE(splitter.Finish().ok());
    ASSERT_EQ(c.payloads.size(), ids.size());
    for (size_t i = 0; i < ids.size(); ++i)
      EXPECT_EQ(c.payloads[i], s.packets[ids[i]]);
  }
}

TEST(StreamSplitterTest, RejectsExtraBytesAndEarlyEnds) {
  const auto& s = ClientTestStream();
  const auto order = PacketOrder(s.header, Progression::kQuality);
  const std::vector<uint32_t> ids(order.begin(), order.begin() + 3);
  const std::string body = SerializeContainer(s, ids);
  {
    Collector c;
    c.expected = ids.size();
    StreamSplitter splitter(true, kNoLimit, c);
    EXPECT_EQ(splitter.Feed(body + "xyz").code(), StatusCode::kParseError);
  }
  {
    Collector c;
    c.expected = ids.size();
    StreamSplitter splitter(true, kNoLimit, c);
    ASSERT_TRUE(splitter.Feed(body.substr(0, body.size() - 1)).ok());
    EXPECT_EQ(splitter.Finish().code(), StatusCode::kParseError);
  }
  {
    Collector c;
    StreamSplitter splitter(true, kNoLimit, c);
    ASSERT_TRUE(splitter.Feed(body.substr(0, 6)).ok());
    EXPECT_FALSE(splitter.Finish().ok());
    EXPECT_FALSE(splitter.Feed("garbage that is not a container").ok());
  }
}

// A header over the client's limit is refused on its length field, from
// the first 8 bytes, before anything more is buffered; one at the limit
// passes.
TEST(StreamSplitterTest, RefusesAHeaderOverTheLimitFromItsLengthField) {
  const auto& s = ClientTestStream();
  const auto order = PacketOrder(s.header, Progression::kQuality);
  const std::vector<uint32_t> ids(order.begin(), order.begin() + 3);
  const std::string body = SerializeContainer(s, ids);
  const uint64_t header_length = testing::HeaderLengthField(body);
  {
    Collector c;
    StreamSplitter splitter(true, header_length - 1, c);
    const Status refused = splitter.Feed(body.substr(0, 8));
    EXPECT_EQ(refused.code(), StatusCode::kParseError);
    EXPECT_NE(refused.message().find("over this client's limit of " +
                                     std::to_string(header_length - 1)),
              std::string::npos)
        << refused.message();
  }
  {
    Collector c;
    c.expected = ids.size();
    StreamSplitter splitter(true, header_length, c);
    ASSERT_TRUE(splitter.Feed(body).ok());
    EXPECT_TRUE(splitter.Finish().ok());
    EXPECT_EQ(c.payloads.size(), ids.size());
  }
}

}  // namespace
}  // namespace meshwave::client
