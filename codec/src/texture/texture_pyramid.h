// The coarser levels of a baked map: 2x2 box filtering of the level above.
// The atlas layout scales exactly (cells and gutters are multiples of the
// factor), so every level keeps the same UVs.
#ifndef MESHWAVE_TEXTURE_TEXTURE_PYRAMID_H_
#define MESHWAVE_TEXTURE_TEXTURE_PYRAMID_H_

#include <cstdint>
#include <vector>

namespace meshwave {

// 8-bit pixels, rows top to bottom, `channels` (3 or 4) a pixel.
struct BakedImage {
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 3;
  std::vector<uint8_t> pixels;
};

// How a map's samples are averaged.
enum class TexelKind : uint8_t {
  kSrgbColor,  // RGB sRGB-encoded (averaged as linear light), alpha linear
  kLinear,     // every channel linear (metallic-roughness, occlusion)
  kNormal,     // RGB a unit vector ((n + 1) / 2): averaged, renormalised
};

// The image at half size (width and height even), each pixel the mean of
// its 2x2 block.
BakedImage HalveImage(const BakedImage& image, TexelKind kind);

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_TEXTURE_PYRAMID_H_
