// Base64 (core/base64.h) against RFC 4648's test vectors (section 10), and
// the URL-safe decoder's refusals.
#include "core/base64.h"

#include <gtest/gtest.h>

#include <string>

namespace meshwave {
namespace {

TEST(Base64Test, Rfc4648Vectors) {
  const char* plain[] = {"", "f", "fo", "foo", "foob", "fooba", "foobar"};
  const char* padded[] = {"", "Zg==", "Zm8=", "Zm9v", "Zm9vYg==", "Zm9vYmE=", "Zm9vYmFy"};
  const char* url[] = {"", "Zg", "Zm8", "Zm9v", "Zm9vYg", "Zm9vYmE", "Zm9vYmFy"};
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(Base64(plain[i]), padded[i]);
    EXPECT_EQ(Base64Url(plain[i]), url[i]);
    EXPECT_EQ(DecodeBase64Url(url[i]), std::string(plain[i]));
  }
}

TEST(Base64Test, UrlAlphabetRoundTripsEveryByte) {
  std::string bytes;
  for (int b = 0; b < 256; ++b) bytes.push_back(static_cast<char>(b));
  const std::string text = Base64Url(bytes);
  EXPECT_EQ(text.find_first_of("+/="), std::string::npos);
  EXPECT_NE(text.find('-'), std::string::npos);
  EXPECT_NE(text.find('_'), std::string::npos);
  EXPECT_EQ(DecodeBase64Url(text), bytes);
}

TEST(Base64Test, UrlDecoderRefusesWhatItDidNotWrite) {
  EXPECT_FALSE(DecodeBase64Url("Zg=="));  // padding
  EXPECT_FALSE(DecodeBase64Url("Z+8"));   // standard alphabet
  EXPECT_FALSE(DecodeBase64Url("Zm9vY"));  // 1 mod 4 digits
  EXPECT_FALSE(DecodeBase64Url("Zh"));     // "f" with stray low bits
  EXPECT_FALSE(DecodeBase64Url("Zm 9v"));
}

}  // namespace
}  // namespace meshwave
