// Parsing of untrusted request parts: targets, numbers, stream queries,
// Range and If-None-Match headers, mesh ids.
#include <gtest/gtest.h>

#include "byte_range.h"
#include "etag.h"
#include "mesh_id.h"
#include "request_target.h"
#include "stream_query.h"

namespace meshwave::server {
namespace {

TEST(RequestTargetTest, SplitsSegmentsAndQuery) {
  auto t = ParseRequestTarget("/v1/meshes/0123456789ab/stream?order=rd&budget=100");
  ASSERT_TRUE(t.ok()) << t.status().ToString();
  EXPECT_EQ(t->segments, (std::vector<std::string>{"v1", "meshes", "0123456789ab", "stream"}));
  EXPECT_EQ(t->query.Get("order").value_or(""), "rd");
  EXPECT_EQ(t->query.Get("budget").value_or(""), "100");
  EXPECT_FALSE(t->query.Get("from"));
}

TEST(RequestTargetTest, DecodesPercentEscapesAndPlus) {
  auto t = ParseRequestTarget("/v1/meshes?name=a%20b+c");
  ASSERT_TRUE(t.ok());
  EXPECT_EQ(t->query.Get("name").value_or(""), "a b c");
  auto root = ParseRequestTarget("/");
  ASSERT_TRUE(root.ok());
  EXPECT_TRUE(root->segments.empty());
}

TEST(RequestTargetTest, RejectsTraversal) {
  for (const char* bad : {"/v1/../etc/passwd", "/v1/meshes/%2e%2e/x", "/v1/%2E%2e",
                          "/v1/meshes/./x", "/v1/meshes/a%2fb", "/v1/meshes/a%5cb",
                          "/v1/meshes/%2e"}) {
    EXPECT_FALSE(ParseRequestTarget(bad).ok()) << bad;
  }
}

TEST(RequestTargetTest, RejectsMalformedTargets) {
  for (const char* bad : {"", "v1/meshes", "http://x/v1", "/v1//meshes", "/v1/meshes/",
                          "/a%zz", "/a%4", "/a%", "/a%00b", "/a%0a", "/a b", "/a#frag",
                          "/a\x01", "/v1?x=1&x=2", "/v1?=3"}) {
    EXPECT_FALSE(ParseRequestTarget(bad).ok()) << bad;
  }
  EXPECT_FALSE(ParseRequestTarget("/" + std::string(kMaxTargetLength, 'a')).ok());
}

TEST(RequestTargetTest, ChecksAllowedQueryKeys) {
  auto t = ParseRequestTarget("/x?limit=1&evil=2");
  ASSERT_TRUE(t.ok());
  EXPECT_FALSE(t->query.CheckAllowed({"limit", "offset"}).ok());
  EXPECT_TRUE(t->query.CheckAllowed({"limit", "evil"}).ok());
}

TEST(ParseUnsignedTest, AcceptsPlainDecimalsInRange) {
  EXPECT_EQ(*ParseUnsigned("0", 10, "x"), 0u);
  EXPECT_EQ(*ParseUnsigned("10", 10, "x"), 10u);
  EXPECT_EQ(*ParseUnsigned("18446744073709551615", ~uint64_t{0}, "x"), ~uint64_t{0});
}

TEST(ParseUnsignedTest, RejectsSignsSpacesAndOverflow) {
  for (const char* bad : {"", "-1", "+1", " 1", "1 ", "0x10", "1e3", "1.5", "11",
                          "99999999999999999999999"}) {
    EXPECT_FALSE(ParseUnsigned(bad, 10, "x").ok()) << bad;
  }
  EXPECT_FALSE(ParseUnsigned("18446744073709551616", ~uint64_t{0}, "x").ok());
}

Result<StreamQuery> Query(const std::string& q) {
  auto t = ParseRequestTarget("/s?" + q);
  if (!t.ok()) return t.status();
  return ParseStreamQuery(t->query);
}

TEST(StreamQueryTest, DefaultsToTheWholeQualityOrder) {
  auto q = Query("");
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->order, Progression::kQuality);
  EXPECT_EQ(q->budget, kMaxBudget);
  EXPECT_EQ(q->max_level, -1);
  EXPECT_EQ(q->from, 0u);
}

TEST(StreamQueryTest, ParsesEveryParameter) {
  auto q = Query("order=resolution&budget=5000&max_level=2&from=7");
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(q->order, Progression::kResolution);
  EXPECT_EQ(q->budget, 5000u);
  EXPECT_EQ(q->max_level, 2);
  EXPECT_EQ(q->from, 7u);
}

TEST(StreamQueryTest, RejectsBadValues) {
  for (const char* bad : {"order=best", "order=", "budget=-1", "budget=abc", "budget=",
                          "budget=18446744073709551616", "budget=1125899906842625",
                          "max_level=-1", "max_level=65", "from=-3", "from=4294967296",
                          "foo=1", "budget=1&budget=2"}) {
    EXPECT_FALSE(Query(bad).ok()) << bad;
  }
}

TEST(ByteRangeTest, ParsesSingleRanges) {
  RangeRequest r = ParseRange("bytes=0-9", 100);
  EXPECT_EQ(r.kind, RangeRequest::kPartial);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.last, 9u);
  r = ParseRange("bytes=90-", 100);
  EXPECT_EQ(r.kind, RangeRequest::kPartial);
  EXPECT_EQ(r.first, 90u);
  EXPECT_EQ(r.last, 99u);
  r = ParseRange("bytes=-10", 100);
  EXPECT_EQ(r.first, 90u);
  EXPECT_EQ(r.last, 99u);
  r = ParseRange("bytes=50-500", 100);
  EXPECT_EQ(r.last, 99u);  // clamped to the end
  r = ParseRange("bytes=-500", 100);
  EXPECT_EQ(r.first, 0u);
}

TEST(ByteRangeTest, RefusesUnsatisfiableRanges) {
  for (const char* bad : {"bytes=100-", "bytes=100-200", "bytes=5-2", "bytes=-0", "bytes=a-b",
                          "bytes=-", "bytes=1", "bytes=99999999999999999999-"}) {
    EXPECT_EQ(ParseRange(bad, 100).kind, RangeRequest::kUnsatisfiable) << bad;
  }
}

TEST(ByteRangeTest, IgnoresOtherUnitsAndMultipleRanges) {
  EXPECT_EQ(ParseRange("items=0-1", 100).kind, RangeRequest::kFull);
  EXPECT_EQ(ParseRange("bytes=0-1,5-6", 100).kind, RangeRequest::kFull);
}

TEST(EtagTest, MatchesListsWeakTagsAndStar) {
  const std::string tag = StrongEtag("abc", "p1");
  EXPECT_EQ(tag, "\"abc-p1\"");
  EXPECT_TRUE(IfNoneMatchMatches("\"abc-p1\"", tag));
  EXPECT_TRUE(IfNoneMatchMatches("\"x\", W/\"abc-p1\"", tag));
  EXPECT_TRUE(IfNoneMatchMatches("*", tag));
  EXPECT_FALSE(IfNoneMatchMatches("\"abc-p2\"", tag));
  EXPECT_FALSE(IfNoneMatchMatches("abc-p1", tag));
}

TEST(MeshIdTest, AcceptsOnlyTwelveLowercaseHexDigits) {
  EXPECT_TRUE(IsValidMeshId("0123456789ab"));
  for (const char* bad : {"", "0123456789a", "0123456789abc", "0123456789AB", "..23456789ab",
                          "0123456789a/", "0123456789ag"}) {
    EXPECT_FALSE(IsValidMeshId(bad)) << bad;
  }
  EXPECT_EQ(MeshIdFromSha256(std::string(64, 'f')), "ffffffffffff");
}

}  // namespace
}  // namespace meshwave::server
