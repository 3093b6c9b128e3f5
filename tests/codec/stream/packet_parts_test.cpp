#include "meshwave/packet_parts.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace meshwave {
namespace {

TEST(PacketPartsTest, PartsJoinAndSplitBack) {
  const std::vector<std::string> parts = {"abc", "", std::string(200, 'x'), "z"};
  const std::string joined = JoinPacketParts(parts);
  // Lengths of all but the last: 3, 0, 200 (two bytes), then the parts.
  EXPECT_EQ(joined.size(), 4u + 3 + 0 + 200 + 1);
  auto back = SplitPacketParts(joined, 4);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  ASSERT_EQ(back->size(), 4u);
  for (size_t p = 0; p < parts.size(); ++p) EXPECT_EQ((*back)[p], parts[p]) << p;
}

TEST(PacketPartsTest, OnePartIsTheWholePayload) {
  const std::vector<std::string> parts = {"codeword"};
  EXPECT_EQ(JoinPacketParts(parts), "codeword");
  auto back = SplitPacketParts("codeword", 1);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->at(0), "codeword");
}

TEST(PacketPartsTest, ATruncatedOrOverrunningTableIsAParseError) {
  // The table ends inside a varint.
  auto truncated = SplitPacketParts(std::string("\x80", 1), 2);
  EXPECT_EQ(truncated.status().code(), StatusCode::kParseError);
  // No table at all for three parts.
  EXPECT_EQ(SplitPacketParts("", 3).status().code(), StatusCode::kParseError);
  // Lengths larger than what follows.
  auto overrun = SplitPacketParts(std::string("\x05") + "abc", 2);
  EXPECT_EQ(overrun.status().code(), StatusCode::kParseError);
  EXPECT_NE(overrun.status().message().find("overrun"), std::string::npos);
  // A varint longer than five bytes.
  EXPECT_EQ(SplitPacketParts(std::string(6, '\xff') + "x", 2).status().code(),
            StatusCode::kParseError);
  EXPECT_EQ(SplitPacketParts("abc", 0).status().code(), StatusCode::kParseError);
}

}  // namespace
}  // namespace meshwave
