// texture_variants IMAGE OUT_DIR: the texture variants the anchors of
// bench/texture_table.sh ship, made the same way for both: the image at
// scale 1, 1/2 and 1/4 (2x2 box averages, as a mip chain), each as a JPEG
// (libjpeg-turbo, 4:2:0, as the codec encodes colour) and as a lossy WebP
// (libwebp, default method 4) at each quality. Writes
// OUT_DIR/s{1,2,4}_q{Q}.jpg and .webp and prints "file<TAB>bytes<TAB>w x h".
//
// Usage: texture_variants IMAGE OUT_DIR [QUALITIES]   (default 50,65,80,95)
#include <webp/encode.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "image/image_decoder.h"
#include "image/image_encoder.h"

namespace {

using meshwave::DecodedImage;

DecodedImage HalfSize(const DecodedImage& in) {
  DecodedImage out;
  out.width = in.width / 2;
  out.height = in.height / 2;
  out.rgba.resize(size_t{out.width} * out.height * 4);
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      for (int c = 0; c < 4; ++c) {
        auto at = [&](uint32_t xx, uint32_t yy) {
          return unsigned{in.rgba[(size_t{yy} * in.width + xx) * 4 + c]};
        };
        const unsigned sum =
            at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
        out.rgba[(size_t{y} * out.width + x) * 4 + c] = static_cast<uint8_t>((sum + 2) / 4);
      }
    }
  }
  return out;
}

bool Write(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    std::fprintf(stderr, "usage: texture_variants IMAGE OUT_DIR [QUALITIES, default 50,65,80,95]\n");
    return argc < 3 ? 2 : 0;
  }
  std::vector<int> qualities;
  std::stringstream list(argc > 3 ? argv[3] : "50,65,80,95");
  for (std::string q; std::getline(list, q, ',');) qualities.push_back(std::stoi(q));
  std::ifstream f(argv[1], std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  meshwave::Result<DecodedImage> image = meshwave::DecodeImage(bytes, {}, argv[1]);
  if (!image.ok()) {
    std::fprintf(stderr, "texture_variants: %s\n", image.status().message().c_str());
    return 1;
  }
  const std::string dir = argv[2];
  DecodedImage level = *image;
  for (int scale = 1; scale <= 4; scale *= 2) {
    const meshwave::ImageView view{level.rgba.data(), level.width, level.height, 4};
    for (int q : qualities) {
      const std::string stem = dir + "/s" + std::to_string(scale) + "_q" + std::to_string(q);
      meshwave::Result<std::string> jpeg = meshwave::EncodeJpeg(view, {q, true});
      uint8_t* webp = nullptr;
      const size_t webp_size =
          WebPEncodeRGBA(level.rgba.data(), static_cast<int>(level.width),
                         static_cast<int>(level.height), static_cast<int>(level.width * 4),
                         static_cast<float>(q), &webp);
      if (!jpeg.ok() || webp_size == 0 || !Write(stem + ".jpg", *jpeg) ||
          !Write(stem + ".webp", std::string(reinterpret_cast<char*>(webp), webp_size))) {
        std::fprintf(stderr, "texture_variants: cannot encode or write %s\n", stem.c_str());
        WebPFree(webp);
        return 1;
      }
      WebPFree(webp);
      std::printf("%s.jpg\t%zu\t%u x %u\n%s.webp\t%zu\t%u x %u\n", stem.c_str(), jpeg->size(),
                  level.width, level.height, stem.c_str(), webp_size, level.width, level.height);
    }
    level = HalfSize(level);
  }
  return 0;
}
