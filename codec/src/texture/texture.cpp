#include "meshwave/texture.h"

namespace meshwave {

std::string_view TextureRoleName(TextureRole role) {
  switch (role) {
    case TextureRole::kBaseColor: return "base colour";
    case TextureRole::kMetallicRoughness: return "metallic-roughness";
    case TextureRole::kNormal: return "normal";
    case TextureRole::kOcclusion: return "occlusion";
    case TextureRole::kEmissive: return "emissive";
  }
  return "unknown";
}

}  // namespace meshwave
