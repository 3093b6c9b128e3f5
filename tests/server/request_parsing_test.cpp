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

// first-last of a kPartial answer, "full", or "416: <problem>".
std::string Range(std::string_view header, uint64_t size) {
  const RangeRequest r = ParseRange(header, size);
  switch (r.kind) {
    case RangeRequest::kFull:
      return "full";
    case RangeRequest::kPartial:
      return std::to_string(r.first) + "-" + std::to_string(r.last);
    case RangeRequest::kUnsatisfiable:
      return "416: " + r.problem;
  }
  return "?";
}

TEST(ByteRangeTest, Rfc9110ExamplesOnATenThousandByteRepresentation) {
  // RFC 9110 14.1.2, "Examples of byte-ranges-specifier values".
  EXPECT_EQ(Range("bytes=0-499", 10000), "0-499");      // the first 500 bytes
  EXPECT_EQ(Range("bytes=500-999", 10000), "500-999");  // the second 500
  EXPECT_EQ(Range("bytes=-500", 10000), "9500-9999");   // the final 500
  EXPECT_EQ(Range("bytes=9500-", 10000), "9500-9999");
  // "The first and last bytes only": two disjoint parts, which would need a
  // multipart body; a server may ignore Range (14.2): the whole.
  EXPECT_EQ(Range("bytes=0-0,-1", 10000), "full");
  // "Other valid (but not canonical) specifications of the second 500
  // bytes": overlapping or adjacent ranges are coalesced (14.2).
  EXPECT_EQ(Range("bytes=500-600,601-999", 10000), "500-999");
  EXPECT_EQ(Range("bytes=500-700,601-999", 10000), "500-999");
}

TEST(ByteRangeTest, Rfc9110ContentRangeExamplesOfA1234ByteRepresentation) {
  // RFC 9110 14.4: requests giving "bytes 42-1233/1234" and the others.
  EXPECT_EQ(Range("bytes=42-1233", 1234), "42-1233");
  EXPECT_EQ(Range("bytes=42-", 1234), "42-1233");
  EXPECT_EQ(Range("bytes=0-499", 1234), "0-499");
  EXPECT_EQ(Range("bytes=500-999", 1234), "500-999");
  EXPECT_EQ(Range("bytes=500-1233", 1234), "500-1233");
  EXPECT_EQ(Range("bytes=734-1233", 1234), "734-1233");
  EXPECT_EQ(Range("bytes=-500", 1234), "734-1233");
  // Past the end the last position is clamped (14.1.2); a longer suffix
  // than the representation is all of it.
  EXPECT_EQ(Range("bytes=500-99999", 1234), "500-1233");
  EXPECT_EQ(Range("bytes=-99999", 1234), "0-1233");
}

TEST(ByteRangeTest, UnitIsCaseInsensitiveAndOtherUnitsAreIgnored) {
  EXPECT_EQ(Range("BYTES=0-5", 100), "0-5");
  EXPECT_EQ(Range("Bytes=0-5", 100), "0-5");
  EXPECT_EQ(Range("items=0-1", 100), "full");
  EXPECT_EQ(Range("bytesx=0-1", 100), "full");
  EXPECT_EQ(Range("bytes =0-1", 100), "full");  // no whitespace before '=' (ABNF): another unit
}

TEST(ByteRangeTest, ListRuleAllowsEmptyElementsAndWhitespace) {
  // RFC 9110 5.6.1: a recipient accepts empty list elements and OWS around
  // the commas.
  EXPECT_EQ(Range("bytes=0-5,", 100), "0-5");
  EXPECT_EQ(Range("bytes=,0-5", 100), "0-5");
  EXPECT_EQ(Range("bytes=, ,0-5 , ", 100), "0-5");
  EXPECT_EQ(Range("bytes= 0-5", 100), "0-5");
  EXPECT_EQ(Range("bytes=0-5\t", 100), "0-5");
  EXPECT_EQ(Range("bytes=0-5 ,\t6-9", 100), "0-9");  // adjacent: one range
  EXPECT_EQ(Range("bytes=0-1,5-6", 100), "full");     // disjoint: the whole
}

TEST(ByteRangeTest, InvalidSpecifiersAreRefusedSayingWhy) {
  const auto problem = [](std::string_view header) {
    const RangeRequest r = ParseRange(header, 100);
    EXPECT_EQ(r.kind, RangeRequest::kUnsatisfiable) << header;
    return r.problem;
  };
  EXPECT_NE(problem("bytes=abc").find("not first-last, first- or -suffix"), std::string::npos);
  EXPECT_NE(problem("bytes=a-b").find("'a-b'"), std::string::npos);
  EXPECT_NE(problem("bytes=1").find("not first-last"), std::string::npos);
  EXPECT_NE(problem("bytes=-").find("not first-last"), std::string::npos);
  EXPECT_NE(problem("bytes=0 - 5").find("not first-last"), std::string::npos);
  EXPECT_NE(problem("bytes=+1-2").find("not first-last"), std::string::npos);
  EXPECT_NE(problem("bytes=5-2").find("ends before it starts"), std::string::npos);
  EXPECT_NE(problem("bytes=").find("lists no range"), std::string::npos);
  EXPECT_NE(problem("bytes=, ,").find("lists no range"), std::string::npos);
  EXPECT_NE(problem("0-5").find("not unit=ranges"), std::string::npos);
  // One invalid element spoils the whole specifier.
  EXPECT_NE(problem("bytes=0-5,x").find("'x'"), std::string::npos);
  // Control bytes are not echoed.
  EXPECT_EQ(problem("bytes=\x01").find('\x01'), std::string::npos);
}

TEST(ByteRangeTest, UnsatisfiableRangesSayWhereTheEndIs) {
  for (const char* bad : {"bytes=100-", "bytes=100-200", "bytes=-0", "bytes=99999999999999999999-",
                          "bytes=100-101,200-"}) {
    const RangeRequest r = ParseRange(bad, 100);
    EXPECT_EQ(r.kind, RangeRequest::kUnsatisfiable) << bad;
    EXPECT_NE(r.problem.find("inside the 100 bytes (positions 0 to 99)"), std::string::npos)
        << r.problem;
  }
  // A suffix of an empty representation is unsatisfiable (14.1.2).
  EXPECT_EQ(ParseRange("bytes=-5", 0).kind, RangeRequest::kUnsatisfiable);
  // One satisfiable range among unsatisfiable ones is served.
  EXPECT_EQ(Range("bytes=500-600,10-19", 100), "10-19");
}

TEST(ByteRangeTest, NumbersTooLargeFor64BitsSaturate) {
  EXPECT_EQ(Range("bytes=0-99999999999999999999999999", 100), "0-99");
  EXPECT_EQ(Range("bytes=-99999999999999999999999999", 100), "0-99");
}

TEST(ByteRangeTest, TooManyRangesAreIgnored) {
  std::string many = "bytes=0-0";
  for (int i = 1; i <= kMaxRanges; ++i) {
    const std::string n = std::to_string(i);
    many.append(",").append(n).append("-").append(n);
  }
  EXPECT_EQ(Range(many, 1000), "full");
}

TEST(EtagTest, IfRangeComparesEntityTagsStronglyAndNeverMatchesADate) {
  const std::string tag = StrongEtag("abc", "");
  EXPECT_TRUE(IfRangeHolds("\"abc\"", tag));
  EXPECT_TRUE(IfRangeHolds(" \"abc\" ", tag));
  EXPECT_FALSE(IfRangeHolds("W/\"abc\"", tag));  // weak: never for If-Range
  EXPECT_FALSE(IfRangeHolds("\"abd\"", tag));
  EXPECT_FALSE(IfRangeHolds("\"abc\", \"x\"", tag));  // one validator, not a list
  EXPECT_FALSE(IfRangeHolds("*", tag));
  // RFC 9110 13.1.5's date form: no Last-Modified is sent, so no date holds.
  EXPECT_FALSE(IfRangeHolds("Sun, 06 Nov 1994 08:49:37 GMT", tag));
  EXPECT_FALSE(IfRangeHolds("", tag));
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
