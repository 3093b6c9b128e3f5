#include "texture/texture_density.h"

#include <cmath>

#include "texture/material_sampler.h"

namespace meshwave {
namespace {

bool HasPixels(const MeshAsset& asset, const TextureRef& ref) {
  return ref.present() && static_cast<size_t>(ref.image) < asset.images.size() &&
         !asset.images[static_cast<size_t>(ref.image)].rgba.empty();
}

}  // namespace

double TexelsOfOriginal(const MeshAsset& asset) {
  if (asset.uv.empty()) return 0;
  const MaterialSampler sampler(asset);
  double sum = 0;
  for (uint32_t f = 0; f < asset.mesh.faces.size(); ++f) {
    const Material& m = sampler.MaterialOf(f);
    const TextureRef* ref = nullptr;
    for (const TextureRef* slot :
         {&m.base_color_texture, &m.emissive_texture, &m.metallic_roughness_texture,
          &m.normal_texture, &m.occlusion_texture}) {
      if (HasPixels(asset, *slot)) {
        ref = slot;
        break;
      }
    }
    if (ref == nullptr) continue;
    Eigen::Vector2f uv[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2f raw = asset.uv.values[asset.uv.faces[f][k]];
      uv[k] = ref->transform * Eigen::Vector3f(raw[0], raw[1], 1.0f);
    }
    const Eigen::Vector2f d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
    const double area =
        0.5 * std::abs(static_cast<double>(d1[0]) * d2[1] - static_cast<double>(d2[0]) * d1[1]);
    const AssetImage& image = asset.images[static_cast<size_t>(ref->image)];
    if (std::isfinite(area)) sum += area * image.width * image.height;
  }
  return sum;
}

}  // namespace meshwave
