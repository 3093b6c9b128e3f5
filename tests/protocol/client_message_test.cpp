// ParseClientMessage (meshwave/client_message.h) on good and bad bytes.
#include "meshwave/client_message.h"

#include <google/protobuf/stubs/logging.h>
#include <gtest/gtest.h>

#include "websocket.pb.h"

namespace meshwave {
namespace {

constexpr char kId[] = "0123456789ab";

std::string Serialize(const proto::ClientMessage& m) {
  return m.SerializeAsString();
}

proto::ClientMessage Start() {
  proto::ClientMessage m;
  m.mutable_start()->set_mesh_id(kId);
  return m;
}

std::string ErrorOf(const std::string& bytes, WsLimits limits = {}) {
  auto r = ParseClientMessage(bytes, limits);
  EXPECT_FALSE(r.ok());
  if (r.ok()) return {};
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  return r.status().message();
}

TEST(ClientMessageTest, ParsesAStartWithDefaults) {
  auto r = ParseClientMessage(Serialize(Start()), {});
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->kind, ClientRequest::Kind::kStart);
  EXPECT_EQ(r->mesh_id, kId);
  EXPECT_EQ(r->stream.order, Progression::kQuality);
  EXPECT_EQ(r->stream.max_level, -1);
  EXPECT_FALSE(r->stream.budget.has_value());
  EXPECT_EQ(r->rate, 0u);
  EXPECT_FALSE(r->header_only);
}

TEST(ClientMessageTest, ParsesEveryField) {
  proto::ClientMessage m = Start();
  m.mutable_start()->set_order("rd");
  m.mutable_start()->set_max_level(0);  // present: level 0, not "all"
  m.mutable_start()->set_budget(5000);
  m.mutable_start()->set_rate(200000);
  auto r = ParseClientMessage(Serialize(m), {});
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->stream.order, Progression::kRd);
  EXPECT_EQ(r->stream.max_level, 0);
  EXPECT_EQ(r->stream.budget, 5000u);
  EXPECT_EQ(r->rate, 200000u);

  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id(kId);
  resume.mutable_resume()->set_order("resolution");
  resume.mutable_resume()->set_cursor(12);
  resume.mutable_resume()->set_budget(0);
  r = ParseClientMessage(Serialize(resume), {});
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->kind, ClientRequest::Kind::kResume);
  EXPECT_EQ(r->stream.order, Progression::kResolution);
  EXPECT_EQ(r->stream.from, 12u);
  EXPECT_EQ(r->stream.budget, 0u);

  proto::ClientMessage refine;
  refine.mutable_refine()->set_extra_bytes(4096);
  r = ParseClientMessage(Serialize(refine), {});
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->kind, ClientRequest::Kind::kRefine);
  EXPECT_EQ(r->extra_bytes, 4096u);
}

TEST(ClientMessageTest, RejectsMalformedBytes) {
  EXPECT_NE(ErrorOf("\xff\xff\xff").find("not a ClientMessage"),
            std::string::npos);
  EXPECT_NE(ErrorOf("").find("holds no request"), std::string::npos);
  // A length prefix running past the end.
  EXPECT_NE(ErrorOf(std::string("\x0a\x40", 2)).find("not a ClientMessage"),
            std::string::npos);
}

TEST(ClientMessageTest, RejectsMessagesOverTheLimit) {
  proto::ClientMessage m = Start();
  m.mutable_start()->set_order(std::string(200, 'q'));
  EXPECT_NE(ErrorOf(Serialize(m), WsLimits{100}).find("the limit is 100"),
            std::string::npos);
}

TEST(ClientMessageTest, RejectsBadIdsOrdersAndNumbers) {
  proto::ClientMessage m = Start();
  m.mutable_start()->set_mesh_id("../etc/passwd");
  EXPECT_NE(ErrorOf(Serialize(m)).find("invalid mesh id"), std::string::npos);

  m = Start();
  m.mutable_start()->set_order("best\x01");
  EXPECT_NE(ErrorOf(Serialize(m)).find("unknown order \"best?\""),
            std::string::npos);

  m = Start();
  m.mutable_start()->set_max_level(kMaxLevelLimit + 1);
  EXPECT_NE(ErrorOf(Serialize(m)).find("max_level"), std::string::npos);

  m = Start();
  m.mutable_start()->set_budget(kMaxBudget + 1);
  EXPECT_NE(ErrorOf(Serialize(m)).find("budget"), std::string::npos);

  m = Start();
  m.mutable_start()->set_rate(kMaxRate + 1);
  EXPECT_NE(ErrorOf(Serialize(m)).find("rate"), std::string::npos);

  m = Start();
  m.mutable_start()->set_header_only(true);
  m.mutable_start()->set_budget(100);
  EXPECT_NE(ErrorOf(Serialize(m)).find("header_only takes no budget"),
            std::string::npos);

  proto::ClientMessage refine;
  refine.mutable_refine();
  EXPECT_NE(ErrorOf(Serialize(refine)).find("at least 1"), std::string::npos);
  refine.mutable_refine()->set_extra_bytes(kMaxBudget + 1);
  EXPECT_NE(ErrorOf(Serialize(refine)).find("extra_bytes"), std::string::npos);

  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id("ABCDEF012345");
  EXPECT_NE(ErrorOf(Serialize(resume)).find("invalid mesh id"),
            std::string::npos);
}

TEST(ClientMessageTest, PacingHasAMinimumRate) {
  proto::ClientMessage m = Start();
  for (uint64_t rate : {uint64_t{1}, kMinRate - 1}) {
    m.mutable_start()->set_rate(rate);
    EXPECT_NE(ErrorOf(Serialize(m)).find("below the minimum of 1024 bytes per second"),
              std::string::npos)
        << rate;
  }
  for (uint64_t rate : {uint64_t{0}, kMinRate}) {
    m.mutable_start()->set_rate(rate);
    auto r = ParseClientMessage(Serialize(m), {});
    ASSERT_TRUE(r.ok()) << rate;
    EXPECT_EQ(r->rate, rate);
  }
  proto::ClientMessage resume;
  resume.mutable_resume()->set_mesh_id(kId);
  resume.mutable_resume()->set_rate(10);
  EXPECT_NE(ErrorOf(Serialize(resume)).find("below the minimum"), std::string::npos);
}

// Counts protobuf's own log lines while alive.
class ProtobufLogCounter {
 public:
  ProtobufLogCounter() {
    count_ = 0;
    previous_ = google::protobuf::SetLogHandler(
        [](google::protobuf::LogLevel, const char*, int, const std::string&) { ++count_; });
  }
  ~ProtobufLogCounter() { google::protobuf::SetLogHandler(previous_); }
  int count() const { return count_; }

 private:
  static inline int count_ = 0;
  google::protobuf::LogHandler* previous_;
};

TEST(ClientMessageTest, InvalidUtf8IsRefusedWithoutALogLine) {
  const std::string bad_utf8 = "\xff\xfe\xc0\x80"
                               "abcdefgh";
  ProtobufLogCounter logs;
  // The counter sees what protobuf logs for invalid UTF-8 in a `string`
  // field (Error.message is one)...
  proto::ServerMessage error;
  error.mutable_error()->set_message("x");
  std::string bytes = error.SerializeAsString();
  bytes.back() = '\xff';
  proto::ServerMessage parsed;
  EXPECT_FALSE(parsed.ParseFromString(bytes));
  ASSERT_EQ(logs.count(), 1);
  // ...and client messages, whose ids and orders are `bytes`, log nothing:
  // the checks of the values refuse them.
  for (int i = 0; i < 3; ++i) {
    proto::ClientMessage m = Start();
    m.mutable_start()->set_mesh_id(bad_utf8);
    EXPECT_NE(ErrorOf(Serialize(m)).find("invalid mesh id"), std::string::npos);
    m = Start();
    m.mutable_start()->set_order(bad_utf8);
    EXPECT_NE(ErrorOf(Serialize(m)).find("unknown order \"????abcdefgh\""), std::string::npos);
    proto::ClientMessage resume;
    resume.mutable_resume()->set_mesh_id(bad_utf8);
    EXPECT_NE(ErrorOf(Serialize(resume)).find("invalid mesh id"), std::string::npos);
  }
  EXPECT_EQ(logs.count(), 1);
}

}  // namespace
}  // namespace meshwave
