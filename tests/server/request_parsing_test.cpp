// Parsing of untrusted request headers: Range, If-Range and If-None-Match.
// (Targets, queries and mesh ids: tests/protocol/.)
#include <gtest/gtest.h>

#include "byte_range.h"
#include "etag.h"

namespace meshwave::server {
namespace {

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

}  // namespace
}  // namespace meshwave::server
