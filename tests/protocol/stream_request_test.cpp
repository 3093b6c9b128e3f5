// A stream request (meshwave/stream_request.h) from GET /stream's query
// and from a WebSocket start or resume (meshwave/client_message.h): the
// same fields give the same request, and the same mistakes the same
// refusal, word for word, over both.
#include "meshwave/stream_request.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/client_message.h"
#include "meshwave/region_text.h"
#include "websocket.pb.h"

namespace meshwave {
namespace {

Result<StreamRequest> Query(const std::string& q) {
  auto t = ParseRequestTarget("/s?" + q);
  if (!t.ok()) return t.status();
  return ParseStreamQuery(t->query);
}

TEST(StreamRequestTest, AnEmptyQueryIsTheWholeQualityOrder) {
  auto q = Query("");
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->order, Progression::kQuality);
  EXPECT_FALSE(q->budget.has_value());
  EXPECT_EQ(q->max_level, -1);
  EXPECT_EQ(q->from, 0u);
}

TEST(StreamRequestTest, AQueryGivesEveryParameter) {
  auto q = Query("order=resolution&budget=5000&max_level=2&from=7");
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->order, Progression::kResolution);
  EXPECT_EQ(q->budget, 5000u);
  EXPECT_EQ(q->max_level, 2);
  EXPECT_EQ(q->from, 7u);
}

TEST(StreamRequestTest, AQueryRefusesBadValues) {
  for (const char* bad : {"order=best", "order=", "budget=-1", "budget=abc", "budget=",
                          "budget=18446744073709551616", "budget=1125899906842625",
                          "max_level=-1", "max_level=65", "from=-3", "from=4294967296",
                          "foo=1", "budget=1&budget=2"}) {
    EXPECT_FALSE(Query(bad).ok()) << bad;
  }
}

// One request written both ways: a query string and a resume message (a
// resume carries every stream field, the cursor included).
struct Both {
  std::string query;
  proto::ClientMessage message;
};

Both Request(const std::vector<std::pair<std::string, std::string>>& fields) {
  Both b;
  auto* r = b.message.mutable_resume();
  r->set_mesh_id("0123456789ab");
  for (const auto& [key, value] : fields) {
    if (!b.query.empty()) b.query += '&';
    b.query += key + "=" + value;
    if (key == "order") r->set_order(value);
    if (key == "budget") r->set_budget(std::stoull(value));
    if (key == "max_level") r->set_max_level(static_cast<uint32_t>(std::stoul(value)));
    if (key == "from") r->set_cursor(static_cast<uint32_t>(std::stoul(value)));
    if (key == "region") r->set_region(value);
    if (key == "view") r->set_view(value);
    if (key == "screen_error") r->set_screen_error(std::stod(value));
    if (key == "held") r->set_held(value);
  }
  return b;
}

Result<StreamRequest> FromMessage(const proto::ClientMessage& m) {
  auto r = ParseClientMessage(m.SerializeAsString(), {});
  if (!r.ok()) return r.status();
  return r->stream;
}

TEST(StreamRequestTest, TheQueryAndTheMessageGiveTheSameRequest) {
  const std::vector<std::vector<std::pair<std::string, std::string>>> cases = {
      {},
      {{"order", "rd"}, {"budget", "5000"}, {"max_level", "2"}, {"from", "7"}},
      {{"order", "resolution"}, {"budget", "0"}},
      {{"region", "0.1,0.2,0,0.3"}, {"budget", "20000"}, {"held", "AQ"}},
      {{"view", "0,0,3,0,0,-1,45,1280,720"}, {"screen_error", "0.75"}, {"max_level", "1"}},
      {{"held", "Aw"}, {"order", "rd"}},
  };
  for (const auto& fields : cases) {
    const Both b = Request(fields);
    auto t = ParseRequestTarget("/s?" + b.query);
    ASSERT_TRUE(t.ok()) << b.query;
    auto http = ParseStreamQuery(t->query);
    auto ws = FromMessage(b.message);
    ASSERT_TRUE(http.ok()) << b.query << ": " << http.status().ToString();
    ASSERT_TRUE(ws.ok()) << b.query << ": " << ws.status().ToString();
    EXPECT_EQ(http->order, ws->order) << b.query;
    EXPECT_EQ(http->budget, ws->budget) << b.query;
    EXPECT_EQ(http->max_level, ws->max_level) << b.query;
    EXPECT_EQ(http->from, ws->from) << b.query;
    EXPECT_EQ(http->region, ws->region) << b.query;
    EXPECT_EQ(http->held, ws->held) << b.query;
    EXPECT_EQ(http->units(), ws->units()) << b.query;
  }
}

TEST(StreamRequestTest, TheQueryAndTheMessageRefuseAlikeSayingTheSame) {
  const std::vector<std::vector<std::pair<std::string, std::string>>> cases = {
      {{"order", "best%C3%A9"}},  // not ASCII: quoted as '?' over both
      {{"order", "quality" + std::string(60, 'x')}},  // quoted at most 40 characters
      {{"budget", "1125899906842625"}},                // 2^50 + 1
      {{"max_level", "65"}},
      {{"region", "0,0,0,1"}, {"view", "0,0,3,0,0,-1,45,100,100"}},
      {{"region", "0,0,0,1"}, {"screen_error", "2"}},
      {{"region", "0,0,0,-1"}},
      {{"view", "0,0,3,0,0,0,45,100,100"}},
      {{"view", "0,0,3,0,0,-1,45,100,100"}, {"screen_error", "20000"}},
      {{"region", "0,0,0,1"}, {"order", "rd"}},
      {{"held", "AQ"}, {"from", "3"}},
      {{"region", "0,0,0,1"}, {"from", "3"}},
  };
  for (const auto& fields : cases) {
    Both b = Request(fields);
    // The message carries the bytes themselves where the query escapes them.
    if (b.message.resume().order().starts_with("best")) {
      b.message.mutable_resume()->set_order("best\xc3\xa9");
    }
    auto t = ParseRequestTarget("/s?" + b.query);
    ASSERT_TRUE(t.ok()) << b.query;
    auto http = ParseStreamQuery(t->query);
    auto ws = FromMessage(b.message);
    ASSERT_FALSE(http.ok()) << b.query;
    ASSERT_FALSE(ws.ok()) << b.query;
    EXPECT_EQ(http.status().code(), StatusCode::kInvalidArgument) << b.query;
    EXPECT_EQ(http.status().message(), ws.status().message()) << b.query;
  }
}

TEST(StreamRequestTest, AnOrderNameIsEchoedQuotedAndCleaned) {
  auto t = ParseRequestTarget("/s?order=%3Cb%3Ebest%C3%A9" + std::string(50, 'z'));
  ASSERT_TRUE(t.ok());
  auto q = ParseStreamQuery(t->query);
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.status().message(),
            "unknown order \"<b>best??" + std::string(31, 'z') + "...\" (quality, resolution, rd)");
}

}  // namespace
}  // namespace meshwave
