#include "appearance_shader.h"

// The codec's sampler, the one the texture bake reads the original through:
// the render then shows the asset as the encoder sees it (same UV
// convention, wrap modes, transform and sRGB handling).
#include "meshwave/asset_appearance.h"

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

PixelShader AppearanceShader(const MeshAsset& asset, bool lit) {
  BaseColorFunction base_color = AssetBaseColor(asset);
  return [base_color, lit](uint32_t face, const Vec3& weights,
                      const Vec3& light) -> std::optional<Rgb8> {
    const std::optional<Eigen::Vector4f> color = base_color(face, weights);
    if (!color) return std::nullopt;  // cut by a masked material
    const Eigen::Vector4f& base = *color;
    // Shaded in linear light (the sampler decodes the sRGB texture and the
    // vertex colours are linear), then encoded to sRGB for the PNG, so a
    // texel under full light comes back to its own byte.
    const auto light_level = lit ? static_cast<float>(weights.dot(light)) : 1.0f;
    Rgb8 out;
    for (int k = 0; k < 3; ++k) out[static_cast<size_t>(k)] = LinearToSrgb8(base[k] * light_level);
    return out;
  };
}

}  // namespace meshwave::cli
