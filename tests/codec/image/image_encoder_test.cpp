// The image encoders: PNG round trips exactly through our decoder, JPEG
// within its quantisation error; bad input gives a Status.
#include "image/image_encoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "image/image_decoder.h"

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

TEST(ImageEncoderTest, RefusesBadInput) {
  const std::vector<uint8_t> pixels(16 * 3, 0);
  EXPECT_FALSE(::meshwave::EncodePng({nullptr, 4, 4, 3}).ok());
  EXPECT_FALSE(::meshwave::EncodePng({pixels.data(), 4, 4, 2}).ok());
  EXPECT_FALSE(::meshwave::EncodePng({pixels.data(), 4, 4, 3}, 10).ok());
  EXPECT_FALSE(::meshwave::EncodeJpeg({pixels.data(), 0, 4, 3}).ok());
  EXPECT_FALSE(::meshwave::EncodeJpeg({pixels.data(), 4, 4, 3}, {0, true}).ok());
}

}  // namespace
}  // namespace meshwave
