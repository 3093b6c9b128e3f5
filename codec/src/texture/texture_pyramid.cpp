#include "texture/texture_pyramid.h"

#include <cmath>

#include "texture/material_sampler.h"

namespace meshwave {

BakedImage HalveImage(const BakedImage& image, TexelKind kind) {
  BakedImage out;
  out.width = image.width / 2;
  out.height = image.height / 2;
  out.channels = image.channels;
  const size_t channels = static_cast<size_t>(image.channels);
  out.pixels.resize(size_t{out.width} * out.height * channels);
  const size_t row = size_t{image.width} * channels;
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      const uint8_t* block[4] = {&image.pixels[2 * y * row + 2 * x * channels],
                                 &image.pixels[2 * y * row + (2 * x + 1) * channels],
                                 &image.pixels[(2 * y + 1) * row + 2 * x * channels],
                                 &image.pixels[(2 * y + 1) * row + (2 * x + 1) * channels]};
      uint8_t* target = &out.pixels[(size_t{y} * out.width + x) * channels];
      float mean[4] = {0, 0, 0, 0};
      for (const uint8_t* p : block) {
        for (size_t c = 0; c < channels; ++c) {
          const bool srgb = kind == TexelKind::kSrgbColor && c < 3;
          mean[c] += 0.25f * (srgb ? SrgbByteToLinear(p[c]) : p[c] / 255.0f);
        }
      }
      if (kind == TexelKind::kNormal) {
        double n[3];
        double length = 0;
        for (int c = 0; c < 3; ++c) {
          n[c] = 2.0 * mean[c] - 1;
          length += n[c] * n[c];
        }
        length = std::sqrt(length);
        for (int c = 0; c < 3; ++c) {
          // Opposed normals cancel: keep the plain mean then.
          const double unit = length > 1e-6 ? n[c] / length : n[c];
          mean[c] = static_cast<float>(0.5 * (unit + 1));
        }
      }
      for (size_t c = 0; c < channels; ++c) {
        const bool srgb = kind == TexelKind::kSrgbColor && c < 3;
        target[c] = srgb ? LinearToSrgbByte(mean[c])
                         : static_cast<uint8_t>(
                               std::lround(std::fmin(std::fmax(mean[c], 0.0f), 1.0f) * 255));
      }
    }
  }
  return out;
}

}  // namespace meshwave
