// The WebSocket transport's reader of server messages, without a socket:
// order checks, the size limit before and after the header, refusals.
#include "ws_server_messages.h"

#include <gtest/gtest.h>

#include "header_limit.h"
#include "websocket.pb.h"

namespace meshwave::client {
namespace {

class Sink final : public StreamSink {
 public:
  Status OnHead(const StreamHead& head) override {
    heads.push_back(head);
    return Status::Ok();
  }
  Status OnBytes(std::string_view) override { return Status::Ok(); }
  Status OnHeaderMessage(std::string_view h) override {
    header = std::string(h);
    return Status::Ok();
  }
  Status OnPacketMessage(size_t cursor, uint32_t id,
                         std::string_view payload) override {
    packets.push_back({cursor, id, std::string(payload)});
    return Status::Ok();
  }
  struct Packet {
    size_t cursor;
    uint32_t id;
    std::string payload;
  };
  std::vector<StreamHead> heads;
  std::string header;
  std::vector<Packet> packets;
};

std::string StartMessage(const std::string& header) {
  proto::ServerMessage m;
  m.mutable_start()->set_header(header);
  auto* s = m.mutable_start()->mutable_selection();
  s->set_next_cursor(2);
  s->set_order_packets(2);
  s->set_bytes(99);
  return m.SerializeAsString();
}
std::string PacketMessage(uint32_t cursor, uint32_t id,
                          const std::string& payload) {
  proto::ServerMessage m;
  m.mutable_packet()->set_cursor(cursor);
  m.mutable_packet()->set_id(id);
  m.mutable_packet()->set_payload(payload);
  return m.SerializeAsString();
}
std::string DoneMessage(uint32_t next) {
  proto::ServerMessage m;
  m.mutable_done()->set_next_cursor(next);
  return m.SerializeAsString();
}

TEST(ServerMessageReaderTest, AStartsAnswerReachesTheSinkInOrder) {
  Sink sink;
  ServerMessageReader reader(true, 1000, sink, "srv");
  EXPECT_EQ(reader.NextMessageLimit(1 << 20), HeaderMessageLimit(1000));
  ASSERT_FALSE(reader.OnMessage(StartMessage("hdr"), true)->has_value());
  EXPECT_EQ(reader.NextMessageLimit(1 << 20), 1u << 20);  // packets now
  ASSERT_FALSE(reader.OnMessage(PacketMessage(0, 5, "ab"), true)->has_value());
  ASSERT_FALSE(reader.OnMessage(PacketMessage(1, 3, "cd"), true)->has_value());
  auto done = reader.OnMessage(DoneMessage(2), true);
  ASSERT_TRUE(done.ok());
  EXPECT_EQ(done->value_or(0), 2u);
  ASSERT_EQ(sink.heads.size(), 1u);
  EXPECT_EQ(sink.heads[0].next_cursor, 2u);
  EXPECT_TRUE(sink.heads[0].complete);
  EXPECT_EQ(sink.heads[0].content_length, 99u);
  EXPECT_EQ(sink.header, "hdr");
  ASSERT_EQ(sink.packets.size(), 2u);
  EXPECT_EQ(sink.packets[1].id, 3u);
  EXPECT_EQ(sink.packets[1].payload, "cd");
}

TEST(ServerMessageReaderTest, RefusesWhatIsOutOfOrderOrMalformed) {
  auto refusal = [](bool expect_header,
                    const std::vector<std::string>& messages, bool binary) {
    Sink sink;
    ServerMessageReader reader(expect_header, 1000, sink, "srv");
    for (const auto& m : messages) {
      auto r = reader.OnMessage(m, binary);
      if (!r.ok()) return r.status();
    }
    return Status::Ok();
  };
  auto expect = [](const Status& s, const std::string& what) {
    EXPECT_EQ(s.code(), StatusCode::kParseError) << s.ToString();
    EXPECT_NE(s.message().find(what), std::string::npos) << s.ToString();
  };
  expect(refusal(true, {PacketMessage(0, 0, "x")}, true),
         "packet before its selection");
  expect(refusal(true, {DoneMessage(0)}, true), "never started");
  expect(refusal(true, {StartMessage("h"), StartMessage("h")}, true),
         "unexpected stream header");
  expect(refusal(false, {StartMessage("h")}, true), "unexpected stream header");
  expect(refusal(true, {StartMessage("h")}, false),
         "does not parse");  // a text frame
  expect(refusal(true, {std::string("\xff\xff\xff", 3)}, true),
         "does not parse");
  expect(refusal(true, {std::string()}, true), "empty message");
  proto::ServerMessage error;
  error.mutable_error()->set_code(proto::Error::NOT_FOUND);
  error.mutable_error()->set_message("no mesh");
  const Status s = refusal(true, {error.SerializeAsString()}, true);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_NE(s.message().find("no mesh"), std::string::npos);
}

TEST(ServerMessageReaderTest, TheHeaderLimitSaysWhatToChange) {
  Sink sink;
  ServerMessageReader reader(true, 1000, sink, "srv");
  const Status s = reader.TooLarge(1 << 20);
  EXPECT_EQ(s.code(), StatusCode::kParseError);
  EXPECT_NE(s.message().find("over this client's limit of 1000 (--max-header)"),
            std::string::npos)
      << s.message();
  EXPECT_EQ(CheckHeaderLength(1000, 1000).code(), StatusCode::kOk);
  EXPECT_EQ(CheckHeaderLength(1001, 1000).code(), StatusCode::kParseError);
}

}  // namespace
}  // namespace meshwave::client
