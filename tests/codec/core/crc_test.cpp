#include "core/crc.h"

#include <gtest/gtest.h>

namespace meshwave {
namespace {

// The catalogue check values (the CRC of "123456789") of both CRCs, as
// reveng's CRC catalogue lists them: CRC-16/IBM-3740 (alias CCITT-FALSE)
// and CRC-32/ISCSI (alias CRC-32C).
TEST(CrcTest, CheckValuesOfTheCatalogue) {
  EXPECT_EQ(Crc16CcittFalse("123456789"), 0x29B1);
  EXPECT_EQ(Crc32c("123456789"), 0xE3069283u);
}

TEST(CrcTest, EmptyInputGivesTheInitialValueAfterTheFinalXor) {
  EXPECT_EQ(Crc16CcittFalse(""), 0xFFFF);
  EXPECT_EQ(Crc32c(""), 0u);
}

TEST(CrcTest, OneFlippedBitChangesBoth) {
  std::string bytes(300, '\x5a');
  const uint16_t c16 = Crc16CcittFalse(bytes);
  const uint32_t c32 = Crc32c(bytes);
  bytes[123] ^= 0x10;
  EXPECT_NE(Crc16CcittFalse(bytes), c16);
  EXPECT_NE(Crc32c(bytes), c32);
}

}  // namespace
}  // namespace meshwave
