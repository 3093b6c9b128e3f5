// The image encoders: PNG round trips exactly through our decoder, JPEG
// and WebP within their quantisation error (WebP's alpha exactly); bad
// input gives a Status. And the encoder's reading of an image's size from
// its header (texture/image_size.h), WebP's three chunk kinds included.
#include "image/image_encoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "image/image_decoder.h"
#include "texture/image_size.h"

namespace meshwave {
namespace {

// A smooth gradient with a little texture: what baked maps look like.
std::vector<uint8_t> Pattern(uint32_t width, uint32_t height, int channels) {
  std::vector<uint8_t> pixels;
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      pixels.push_back(static_cast<uint8_t>(x * 255 / width));
      pixels.push_back(static_cast<uint8_t>(y * 255 / height));
      pixels.push_back(static_cast<uint8_t>(128 + 60 * std::sin(0.2 * (x + y))));
      if (channels == 4) pixels.push_back(static_cast<uint8_t>((x + y) % 2 == 0 ? 255 : 100));
    }
  }
  return pixels;
}

TEST(ImageEncoderTest, PngRoundTripsExactly) {
  for (int channels : {3, 4}) {
    const std::vector<uint8_t> pixels = Pattern(37, 21, channels);
    auto png = ::meshwave::EncodePng({pixels.data(), 37, 21, channels});
    ASSERT_TRUE(png.ok()) << png.status().ToString();
    EXPECT_EQ(SniffImageFormat(*png), ImageFormat::kPng);
    auto decoded = DecodeImage(*png, {}, "round trip");
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    ASSERT_EQ(decoded->width, 37u);
    ASSERT_EQ(decoded->height, 21u);
    for (size_t i = 0; i < size_t{37} * 21; ++i) {
      for (int c = 0; c < 4; ++c) {
        const uint8_t want = c < channels ? pixels[i * static_cast<size_t>(channels) + c] : 255;
        ASSERT_EQ(decoded->rgba[i * 4 + static_cast<size_t>(c)], want) << "pixel " << i;
      }
    }
  }
}

TEST(ImageEncoderTest, JpegRoundTripsWithinItsError) {
  const std::vector<uint8_t> pixels = Pattern(64, 48, 3);
  for (bool subsample : {true, false}) {
    auto jpeg = ::meshwave::EncodeJpeg({pixels.data(), 64, 48, 3}, {95, subsample});
    ASSERT_TRUE(jpeg.ok()) << jpeg.status().ToString();
    EXPECT_EQ(SniffImageFormat(*jpeg), ImageFormat::kJpeg);
    auto decoded = DecodeImage(*jpeg, {}, "round trip");
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    ASSERT_EQ(decoded->width, 64u);
    ASSERT_EQ(decoded->height, 48u);
    double error = 0;
    for (size_t i = 0; i < size_t{64} * 48; ++i) {
      for (size_t c = 0; c < 3; ++c) {
        error += std::abs(decoded->rgba[i * 4 + c] - pixels[i * 3 + c]);
      }
      EXPECT_EQ(decoded->rgba[i * 4 + 3], 255);
    }
    EXPECT_LT(error / (64 * 48 * 3), 2.0) << (subsample ? "4:2:0" : "4:4:4");
  }
}

TEST(ImageEncoderTest, WebpRoundTripsWithinItsErrorAndKeepsAlphaExactly) {
  for (int channels : {3, 4}) {
    const std::vector<uint8_t> pixels = Pattern(64, 48, channels);
    auto webp = ::meshwave::EncodeWebp({pixels.data(), 64, 48, channels}, 90);
    ASSERT_TRUE(webp.ok()) << webp.status().ToString();
    EXPECT_EQ(SniffImageFormat(*webp), ImageFormat::kWebp);
    // RGB is a plain lossy VP8 chunk; alpha makes it an extended (VP8X) file.
    EXPECT_EQ(webp->substr(12, 4), channels == 3 ? "VP8 " : "VP8X");
    auto size = ReadImageSize(*webp, "image/webp");
    ASSERT_TRUE(size.ok()) << size.status().ToString();
    EXPECT_EQ(size->width, 64u);
    EXPECT_EQ(size->height, 48u);
    auto decoded = DecodeImage(*webp, {}, "round trip");
    ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
    double error = 0;
    for (size_t i = 0; i < size_t{64} * 48; ++i) {
      for (size_t c = 0; c < 3; ++c) {
        error += std::abs(decoded->rgba[i * 4 + c] -
                          pixels[i * static_cast<size_t>(channels) + c]);
      }
      const uint8_t alpha = channels == 4 ? pixels[i * 4 + 3] : 255;
      ASSERT_EQ(decoded->rgba[i * 4 + 3], alpha) << "pixel " << i;
    }
    EXPECT_LT(error / (64 * 48 * 3), 4.0) << channels;
  }
}

TEST(ImageEncoderTest, ImageSizeReadsEachHeaderAndRefusesOthers) {
  const std::vector<uint8_t> pixels = Pattern(40, 24, 3);
  auto jpeg = ::meshwave::EncodeJpeg({pixels.data(), 40, 24, 3});
  auto png = ::meshwave::EncodePng({pixels.data(), 40, 24, 3});
  auto webp = ::meshwave::EncodeWebp({pixels.data(), 40, 24, 3}, 50);
  ASSERT_TRUE(jpeg.ok() && png.ok() && webp.ok());
  for (const auto& [bytes, mime] : {std::pair{*jpeg, "image/jpeg"}, std::pair{*png, "image/png"},
                                    std::pair{*webp, "image/webp"}}) {
    auto size = ReadImageSize(bytes, mime);
    ASSERT_TRUE(size.ok()) << mime << ": " << size.status().ToString();
    EXPECT_EQ(size->width, 40u) << mime;
    EXPECT_EQ(size->height, 24u) << mime;
  }
  // A lossless (VP8L) header: signature 0x2f, then width - 1 and height - 1
  // in 14 bits each, little-endian.
  std::string lossless("RIFF\x1a\0\0\0WEBPVP8L\x0e\0\0\0\x2f", 21);
  const uint32_t bits = (300 - 1) | (200 - 1) << 14;
  for (int i = 0; i < 4; ++i) lossless += static_cast<char>(bits >> (8 * i) & 0xff);
  lossless += std::string(10, '\0');
  auto size = ReadImageSize(lossless, "image/webp");
  ASSERT_TRUE(size.ok()) << size.status().ToString();
  EXPECT_EQ(size->width, 300u);
  EXPECT_EQ(size->height, 200u);
  EXPECT_FALSE(ReadImageSize(*jpeg, "image/webp").ok());
  EXPECT_FALSE(ReadImageSize(webp->substr(0, 20), "image/webp").ok());
  EXPECT_FALSE(ReadImageSize(*webp, "image/gif").ok());
  std::string unknown = *webp;
  unknown.replace(12, 4, "ALPH");
  EXPECT_FALSE(ReadImageSize(unknown, "image/webp").ok());
}

TEST(ImageEncoderTest, RefusesBadInput) {
  const std::vector<uint8_t> pixels(16 * 3, 0);
  EXPECT_FALSE(::meshwave::EncodePng({nullptr, 4, 4, 3}).ok());
  EXPECT_FALSE(::meshwave::EncodePng({pixels.data(), 4, 4, 2}).ok());
  EXPECT_FALSE(::meshwave::EncodePng({pixels.data(), 4, 4, 3}, 10).ok());
  EXPECT_FALSE(::meshwave::EncodeJpeg({pixels.data(), 0, 4, 3}).ok());
  EXPECT_FALSE(::meshwave::EncodeJpeg({pixels.data(), 4, 4, 3}, {0, true}).ok());
  EXPECT_FALSE(::meshwave::EncodeWebp({pixels.data(), 4, 4, 3}, 101).ok());
  EXPECT_FALSE(::meshwave::EncodeWebp({pixels.data(), 4, 4, 5}, 50).ok());
}

}  // namespace
}  // namespace meshwave
