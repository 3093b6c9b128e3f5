// The texture decoders: every PNG layout to RGBA8, JPEG (grey, colour,
// CMYK refused), WebP, sniffing by magic bytes, and the refusals: pixel
// limits from the header (decompression bombs), truncated and corrupt data.
#include "image/image_decoder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <turbojpeg.h>
#include <webp/encode.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "codec/image/png_encoder_testonly.h"

namespace meshwave {
namespace {

using testing::BombPng;
using testing::EncodePng;
using ::testing::HasSubstr;
using testing::PngChunk;
using testing::PngSpec;

std::vector<uint8_t> Pixel(const DecodedImage& image, uint32_t x, uint32_t y) {
  const size_t at = (size_t{y} * image.width + x) * 4;
  return {image.rgba[at], image.rgba[at + 1], image.rgba[at + 2],
          image.rgba[at + 3]};
}

std::vector<uint8_t> Rgba(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  return {r, g, b, a};
}

// A w x h RGB gradient (8-bit samples), the same for every encoder.
std::vector<uint16_t> Gradient(uint32_t w, uint32_t h, int channels) {
  std::vector<uint16_t> out;
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const uint16_t v[4] = {static_cast<uint16_t>(x * 255 / (w - 1)),
                             static_cast<uint16_t>(y * 255 / (h - 1)),
                             static_cast<uint16_t>((x + y) % 256), 200};
      for (int c = 0; c < channels; ++c) out.push_back(v[c]);
    }
  }
  return out;
}

std::string Jpeg(uint32_t w, uint32_t h, int pixel_format, int subsampling) {
  const int channels = tjPixelSize[pixel_format];
  std::vector<unsigned char> pixels(size_t{w} * h * channels);
  for (size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = static_cast<unsigned char>(i * 7);
  tjhandle handle = tjInitCompress();
  unsigned char* out = nullptr;
  unsigned long size = 0;
  const int rc = tjCompress2(handle, pixels.data(), static_cast<int>(w), 0,
                             static_cast<int>(h), pixel_format, &out, &size,
                             subsampling, 90, 0);
  EXPECT_EQ(rc, 0) << tjGetErrorStr2(handle);
  std::string bytes(reinterpret_cast<char*>(out), size);
  tjFree(out);
  tjDestroy(handle);
  return bytes;
}

TEST(ImageDecoderTest, SniffsByMagicBytes) {
  EXPECT_EQ(SniffImageFormat("\x89PNG\r\n\x1a\nrest"), ImageFormat::kPng);
  EXPECT_EQ(SniffImageFormat("\xff\xd8\xff\xe0"), ImageFormat::kJpeg);
  EXPECT_EQ(SniffImageFormat(std::string_view("RIFF\x10\0\0\0WEBPVP8 ", 16)),
            ImageFormat::kWebp);
  EXPECT_EQ(SniffImageFormat("GIF89a"), ImageFormat::kUnknown);
  EXPECT_EQ(SniffImageFormat(""), ImageFormat::kUnknown);
  EXPECT_EQ(ImageMimeType(ImageFormat::kWebp), std::string("image/webp"));
}

TEST(ImageDecoderTest, RefusesOtherFormatsNamingThem) {
  const auto gif = DecodeImage("GIF89a\x01\0\x01\0", {}, "t.png");
  EXPECT_EQ(gif.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(gif.status().message(),
              HasSubstr("t.png: image format GIF is not supported"));
  const auto ktx = DecodeImage("\xabKTX 20\xbb\r\n\x1a\n", {}, "k");
  EXPECT_THAT(ktx.status().message(), HasSubstr("KTX2"));
  const auto other = DecodeImage("<!DOCTYPE", {}, "x");
  EXPECT_THAT(other.status().message(),
              HasSubstr("unknown (starts 3c 21 44 4f)"));
}

TEST(ImageDecoderTest, DecodesRgbAndRgbaPng) {
  for (int type : {2, 6}) {
    PngSpec spec;
    spec.width = 5;
    spec.height = 3;
    spec.color_type = type;
    const auto samples = Gradient(5, 3, type == 2 ? 3 : 4);
    const auto image = DecodeImage(EncodePng(spec, samples), {}, "g.png");
    ASSERT_TRUE(image.ok()) << image.status().ToString();
    EXPECT_EQ(image->width, 5u);
    EXPECT_EQ(image->height, 3u);
    EXPECT_EQ(Pixel(*image, 4, 2), Rgba(255, 255, 6, type == 2 ? 255 : 200));
    EXPECT_EQ(Pixel(*image, 0, 0), Rgba(0, 0, 0, type == 2 ? 255 : 200));
  }
}

TEST(ImageDecoderTest, ExpandsGreyPaletteAndLowBitDepths) {
  PngSpec grey1;
  grey1.width = 9;  // a partial last byte
  grey1.height = 2;
  grey1.color_type = 0;
  grey1.bit_depth = 1;
  std::vector<uint16_t> bits(18, 0);
  bits[8] = 1;
  bits[9] = 1;
  const auto g = DecodePng(EncodePng(grey1, bits), {}, "g1");
  ASSERT_TRUE(g.ok()) << g.status().ToString();
  EXPECT_EQ(Pixel(*g, 8, 0), Rgba(255, 255, 255, 255));
  EXPECT_EQ(Pixel(*g, 0, 1), Rgba(255, 255, 255, 255));
  EXPECT_EQ(Pixel(*g, 1, 1), Rgba(0, 0, 0, 255));

  PngSpec palette;
  palette.width = 3;
  palette.height = 1;
  palette.color_type = 3;
  palette.bit_depth = 4;
  palette.palette = {{{255, 0, 0}}, {{0, 255, 0}}, {{0, 0, 255}}};
  palette.trns = std::string("\xff\x80", 2);  // entry 1 half transparent
  const auto p = DecodePng(EncodePng(palette, {0, 1, 2}), {}, "p");
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_EQ(Pixel(*p, 0, 0), Rgba(255, 0, 0, 255));
  EXPECT_EQ(Pixel(*p, 1, 0), Rgba(0, 255, 0, 128));
  EXPECT_EQ(Pixel(*p, 2, 0), Rgba(0, 0, 255, 255));

  PngSpec grey_alpha;
  grey_alpha.width = 2;
  grey_alpha.color_type = 4;
  const auto ga = DecodePng(EncodePng(grey_alpha, {10, 20, 30, 40}), {}, "ga");
  ASSERT_TRUE(ga.ok()) << ga.status().ToString();
  EXPECT_EQ(Pixel(*ga, 1, 0), Rgba(30, 30, 30, 40));
}

TEST(ImageDecoderTest, ScalesSixteenBitSamples) {
  PngSpec spec;
  spec.width = 3;
  spec.color_type = 0;
  spec.bit_depth = 16;
  const auto image = DecodePng(EncodePng(spec, {0, 0x8080, 0xffff}), {}, "16");
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  EXPECT_EQ(Pixel(*image, 0, 0), Rgba(0, 0, 0, 255));
  EXPECT_EQ(Pixel(*image, 1, 0), Rgba(128, 128, 128, 255));
  EXPECT_EQ(Pixel(*image, 2, 0), Rgba(255, 255, 255, 255));
}

TEST(ImageDecoderTest, InterlacedPngDecodesLikeTheProgressiveOne) {
  PngSpec spec;
  spec.width = 13;
  spec.height = 11;
  spec.color_type = 6;
  const auto samples = Gradient(13, 11, 4);
  const auto plain = DecodePng(EncodePng(spec, samples), {}, "plain");
  spec.interlaced = true;
  const auto adam7 = DecodePng(EncodePng(spec, samples), {}, "adam7");
  ASSERT_TRUE(plain.ok() && adam7.ok()) << adam7.status().ToString();
  EXPECT_EQ(plain->rgba, adam7->rgba);
}

TEST(ImageDecoderTest, RefusesAPngBombFromItsHeader) {
  // 100,000 x 100,000 declared, a few bytes of data: refused before any
  // pixel buffer exists.
  const std::string png = BombPng(100000, 100000);
  const auto image = DecodeImage(png, {}, "bomb.png");
  EXPECT_EQ(image.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(
      image.status().message(),
      HasSubstr("bomb.png: PNG declares 100000x100000 = 10000000000 "
                "pixels, more than the 67108864-pixel limit per image"));
  // A lower limit is honoured too, and so is a byte budget.
  PngSpec small;
  small.width = 64;
  small.height = 64;
  const std::string ok = EncodePng(small, Gradient(64, 64, 3));
  EXPECT_EQ(DecodeImage(ok, {.max_pixels = 4095}, "s").status().code(),
            StatusCode::kUnsupported);
  EXPECT_THAT(DecodeImage(ok, {.max_pixels = 4096, .max_bytes = 1000}, "s")
                  .status()
                  .message(),
              HasSubstr("past their byte limit"));
  EXPECT_TRUE(DecodeImage(ok, {.max_pixels = 4096}, "s").ok());
}

TEST(ImageDecoderTest, SkipsAncillaryChunksWhateverTheyClaim) {
  // An embedded colour profile whose header claims 1.9 GB, a text chunk and
  // an unknown chunk: none shapes the pixels, so none is read, and the image
  // decodes as it would without them.
  PngSpec spec;
  spec.width = 8;
  spec.height = 4;
  const std::string plain = EncodePng(spec, Gradient(8, 4, 3));
  std::string profile(132, '\0');
  const uint32_t claimed = 0x73000000;
  for (int i = 0; i < 4; ++i) profile[i] = char(claimed >> (24 - 8 * i));
  profile.replace(12, 12, "mntrRGB XYZ ");
  profile.replace(36, 4, "acsp");
  uLongf packed_size = compressBound(profile.size());
  std::string packed(packed_size, '\0');
  ASSERT_EQ(compress(reinterpret_cast<Bytef*>(packed.data()), &packed_size,
                     reinterpret_cast<const Bytef*>(profile.data()),
                     profile.size()),
            Z_OK);
  packed.resize(packed_size);
  std::string chunks;
  PngChunk(chunks, "iCCP", std::string("icc\0\0", 5) + packed);
  PngChunk(chunks, "tEXt", std::string("Comment\0", 8) + "hello");
  PngChunk(chunks, "vpAg", std::string(9, '\1'));
  constexpr size_t kAfterHeader = 8 + 25;  // signature, IHDR
  const std::string with_chunks =
      plain.substr(0, kAfterHeader) + chunks + plain.substr(kAfterHeader);
  const auto expected = DecodePng(plain, {}, "plain");
  const auto image = DecodePng(with_chunks, {}, "chunks");
  ASSERT_TRUE(expected.ok() && image.ok()) << image.status().ToString();
  EXPECT_EQ(image->rgba, expected->rgba);
}

TEST(ImageDecoderTest, RefusesTruncatedAndCorruptPng) {
  PngSpec spec;
  spec.width = 40;
  spec.height = 40;
  const std::string png = EncodePng(spec, Gradient(40, 40, 3));
  for (size_t cut :
       {size_t{8}, size_t{20}, size_t{40}, png.size() / 2, png.size() - 5}) {
    const auto image = DecodePng(png.substr(0, cut), {}, "cut.png");
    EXPECT_EQ(image.status().code(), StatusCode::kParseError) << cut;
    EXPECT_THAT(image.status().message(), HasSubstr("cut.png: PNG")) << cut;
  }
  EXPECT_THAT(DecodePng(png.substr(0, png.size() / 2), {}, "cut.png")
                  .status()
                  .message(),
              HasSubstr("truncated"));
  std::string corrupt = png;
  corrupt[png.size() / 2] ^= 0x55;  // inside IDAT: a CRC error
  EXPECT_EQ(DecodePng(corrupt, {}, "c").status().code(),
            StatusCode::kParseError);
  PngSpec empty;
  empty.width = 0;
  empty.raw_override = true;
  EXPECT_EQ(DecodePng(EncodePng(empty, {}), {}, "e").status().code(),
            StatusCode::kParseError);
}

TEST(ImageDecoderTest, DecodesColourAndGreyJpeg) {
  const auto colour =
      DecodeImage(Jpeg(16, 8, TJPF_RGB, TJSAMP_420), {}, "c.jpg");
  ASSERT_TRUE(colour.ok()) << colour.status().ToString();
  EXPECT_EQ(colour->width, 16u);
  EXPECT_EQ(colour->height, 8u);
  EXPECT_EQ(colour->rgba.size(), 16u * 8 * 4);
  EXPECT_EQ(colour->rgba[3], 255);
  const auto grey =
      DecodeImage(Jpeg(9, 7, TJPF_GRAY, TJSAMP_GRAY), {}, "g.jpg");
  ASSERT_TRUE(grey.ok()) << grey.status().ToString();
  for (size_t i = 0; i < grey->rgba.size(); i += 4) {
    EXPECT_EQ(grey->rgba[i], grey->rgba[i + 1]);
    EXPECT_EQ(grey->rgba[i], grey->rgba[i + 2]);
    EXPECT_EQ(grey->rgba[i + 3], 255);
  }
}

TEST(ImageDecoderTest, RefusesCmykJpeg) {
  const auto cmyk = DecodeImage(Jpeg(8, 8, TJPF_CMYK, TJSAMP_444), {}, "p.jpg");
  EXPECT_EQ(cmyk.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(cmyk.status().message(),
              HasSubstr("p.jpg: CMYK JPEG is not supported"));
}

TEST(ImageDecoderTest, RefusesAJpegBombFromItsHeader) {
  std::string jpeg = Jpeg(16, 16, TJPF_RGB, TJSAMP_444);
  // The frame header (SOF0): FF C0, length, precision, height, width.
  const size_t sof = jpeg.find("\xff\xc0");
  ASSERT_NE(sof, std::string::npos);
  // 65,000 x 65,000 (libjpeg's own limit is 65,500 a side).
  jpeg[sof + 5] = jpeg[sof + 7] = '\xfd';
  jpeg[sof + 6] = jpeg[sof + 8] = '\xe8';
  const auto image = DecodeImage(jpeg, {}, "bomb.jpg");
  EXPECT_EQ(image.status().code(), StatusCode::kUnsupported);
  EXPECT_THAT(
      image.status().message(),
      HasSubstr("bomb.jpg: JPEG declares 65000x65000 = 4225000000 pixels, "
                "more than the 67108864-pixel limit per image"));
}

TEST(ImageDecoderTest, RefusesTruncatedJpeg) {
  const std::string jpeg = Jpeg(64, 64, TJPF_RGB, TJSAMP_420);
  for (size_t cut : {size_t{3}, size_t{30}, jpeg.size() / 2, jpeg.size() - 2}) {
    const auto image = DecodeJpeg(jpeg.substr(0, cut), {}, "t.jpg");
    EXPECT_EQ(image.status().code(), StatusCode::kParseError) << cut;
    EXPECT_THAT(image.status().message(), HasSubstr("t.jpg: JPEG")) << cut;
  }
}

TEST(ImageDecoderTest, DecodesWebpAndRefusesTruncatedWebp) {
  std::vector<uint8_t> rgba(12 * 10 * 4);
  for (size_t i = 0; i < rgba.size(); ++i)
    rgba[i] = static_cast<uint8_t>(i * 13);
  uint8_t* out = nullptr;
  const size_t size = WebPEncodeLosslessRGBA(rgba.data(), 12, 10, 48, &out);
  ASSERT_GT(size, 0u);
  const std::string webp(reinterpret_cast<char*>(out), size);
  WebPFree(out);
  const auto image = DecodeImage(webp, {}, "l.webp");
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  EXPECT_EQ(image->rgba, rgba);  // lossless
  const auto cut = DecodeImage(webp.substr(0, webp.size() / 2), {}, "l.webp");
  EXPECT_EQ(cut.status().code(), StatusCode::kParseError);
  EXPECT_THAT(cut.status().message(), HasSubstr("l.webp: WebP"));
  EXPECT_EQ(DecodeImage(webp, {.max_pixels = 100}, "l.webp").status().code(),
            StatusCode::kUnsupported);
}

}  // namespace
}  // namespace meshwave
