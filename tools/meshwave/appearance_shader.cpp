#include "appearance_shader.h"

#include <memory>

// The codec's sampler, the one the texture bake reads the original through:
// the render then shows the asset as the encoder sees it (same UV
// convention, wrap modes, transform and sRGB handling).
#include "texture/material_sampler.h"

namespace meshwave::cli {

bool HasAppearance(const MeshAsset& asset) {
  if (!asset.color.empty()) return true;
  for (const Material& m : asset.materials) {
    if (m.base_color_texture.present() || m.base_color_factor != Eigen::Vector4f::Ones()) {
      return true;
    }
  }
  return false;
}

PixelShader AppearanceShader(const MeshAsset& asset) {
  auto sampler = std::make_shared<const MaterialSampler>(asset);
  return [sampler](uint32_t face, const Vec3& weights, const Vec3& light) -> std::optional<Rgb8> {
    const Eigen::Vector4f base = sampler->BaseColor(face, weights);
    if (sampler->MaterialOf(face).alpha_mode == AlphaMode::kMask && base[3] == 0) {
      return std::nullopt;
    }
    // Shaded in linear light (the sampler decodes the sRGB texture and the
    // vertex colours are linear), then encoded to sRGB for the PNG, so a
    // texel under full light comes back to its own byte.
    const auto lit = static_cast<float>(weights.dot(light));
    Rgb8 out;
    for (int k = 0; k < 3; ++k) out[static_cast<size_t>(k)] = LinearToSrgbByte(base[k] * lit);
    return out;
  };
}

}  // namespace meshwave::cli
