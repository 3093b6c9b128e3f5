#include "meshwave/asset_appearance.h"

#include <memory>

#include "texture/material_sampler.h"

namespace meshwave {

BaseColorFunction AssetBaseColor(const MeshAsset& asset) {
  auto sampler = std::make_shared<const MaterialSampler>(asset);
  return [sampler](uint32_t face, const Vec3& w) -> std::optional<Eigen::Vector4f> {
    const Eigen::Vector4f base = sampler->BaseColor(face, w);
    if (sampler->MaterialOf(face).alpha_mode == AlphaMode::kMask && base[3] == 0) {
      return std::nullopt;
    }
    return base;
  };
}

uint8_t LinearToSrgb8(float linear) { return LinearToSrgbByte(linear); }

}  // namespace meshwave
