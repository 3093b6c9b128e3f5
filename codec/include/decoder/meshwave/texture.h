// Textures of a semi-regular stream: maps baked into the atlas of the base
// mesh (docs/FORMAT.md, "Texture atlas"), each a pyramid of whole encoded
// images (JPEG or PNG) that travel as packets of their own. The encoder
// makes them (meshwave/texture_bake.h); the decoder hands out the best
// level it holds and every vertex's texture coordinates, which never
// travel: the atlas gives them.
#ifndef MESHWAVE_TEXTURE_H_
#define MESHWAVE_TEXTURE_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace meshwave {

// What a map holds, as glTF 2.0's metallic-roughness material names it.
enum class TextureRole : uint8_t {
  kBaseColor = 0,          // sRGB RGB (+ linear alpha)
  kMetallicRoughness = 1,  // G: roughness, B: metallic; R: occlusion when baked together
  kNormal = 2,             // tangent space of the atlas
  kOcclusion = 3,          // R
  kEmissive = 4,           // sRGB RGB
};

std::string_view TextureRoleName(TextureRole role);  // "base colour", ...

// The atlas's parameters (AtlasLayout): square cells of `cell` texels, a
// gutter of `gutter` texels around each base face's triangle, `columns`
// cells a row, two base faces a cell.
struct TextureAtlas {
  uint32_t cell = 0;
  uint32_t gutter = 0;
  uint32_t columns = 0;
};

// The scalars of the one material a textured stream has: what the maps do
// not hold (a factor whose map is baked is 1).
struct TextureMaterial {
  float metallic_factor = 1.0f;
  float roughness_factor = 1.0f;
  Eigen::Vector3f emissive_factor{0.0f, 0.0f, 0.0f};
  float normal_scale = 1.0f;
  float occlusion_strength = 1.0f;
  bool alpha_blend = false;  // base colour alpha is transparency (else opaque)
  bool double_sided = false;
};

struct TextureMap {
  TextureRole role = TextureRole::kBaseColor;
  std::string mime_type;  // image/jpeg or image/png
  // Encoded images, coarsest first: level k of L is the atlas's size
  // divided by 2^(L-1-k) (the last level is full size). Each is whole.
  std::vector<std::string> levels;
};

// The textures of one mesh: what EncodeMesh codes (VertexAttributes) and
// what the decoder's header describes.
struct BakedTexture {
  TextureAtlas atlas;
  TextureMaterial material;
  std::vector<TextureMap> maps;
};

// A map as a stream's header describes it (ProgressiveDecoder::texture()).
struct TextureLevelSize {
  uint32_t width = 0;
  uint32_t height = 0;
};
struct TextureMapInfo {
  TextureRole role = TextureRole::kBaseColor;
  std::string mime_type;
  std::vector<TextureLevelSize> levels;  // coarsest first
};
struct TextureInfo {
  TextureAtlas atlas;
  TextureMaterial material;
  std::vector<TextureMapInfo> maps;
};

// The finest level of a map a decoder holds: one whole encoded image.
struct TextureImage {
  TextureRole role = TextureRole::kBaseColor;
  std::string mime_type;
  int level = 0;  // of the map's levels, coarsest 0
  uint32_t width = 0;
  uint32_t height = 0;
  std::string_view bytes;  // the decoder's copy: valid until Reset or its end
};

}  // namespace meshwave

#endif  // MESHWAVE_TEXTURE_H_
