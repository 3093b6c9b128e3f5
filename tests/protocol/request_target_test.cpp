// Request targets (meshwave/request_target.h): segments and query
// parameters of an untrusted target, decimal numbers; mesh ids
// (meshwave/mesh_id.h).
#include "meshwave/request_target.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshwave/mesh_id.h"

namespace meshwave {
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
  // Built in place: "/" + std::string(...) trips GCC 12's -Wrestrict (a
  // false positive in libstdc++'s operator+).
  std::string long_target(kMaxTargetLength + 1, 'a');
  long_target[0] = '/';
  EXPECT_FALSE(ParseRequestTarget(long_target).ok());
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

TEST(MeshIdTest, AcceptsOnlyTwelveLowercaseHexDigits) {
  EXPECT_TRUE(IsValidMeshId("0123456789ab"));
  for (const char* bad : {"", "0123456789a", "0123456789abc", "0123456789AB", "..23456789ab",
                          "0123456789a/", "0123456789ag"}) {
    EXPECT_FALSE(IsValidMeshId(bad)) << bad;
  }
  EXPECT_EQ(MeshIdFromSha256(std::string(64, 'f')), "ffffffffffff");
}

}  // namespace
}  // namespace meshwave
