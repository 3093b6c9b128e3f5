// glTF materials, textures and samplers as meshwave Materials: the
// metallic-roughness core, KHR_texture_transform per slot, EXT_texture_webp
// sources. A slot that reads TEXCOORD_1 or later, or whose texture has only
// a KTX2 source, is dropped with a note; an index out of range is an error.
#ifndef MESHWAVE_ASSET_GLTF_MATERIALS_H_
#define MESHWAVE_ASSET_GLTF_MATERIALS_H_

#include <string>
#include <string_view>
#include <vector>

#include "asset/tiny_gltf_config.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

// One Material per glTF material, in order; TextureRef::image is the glTF
// image index. Notes go to `notes`.
Result<std::vector<Material>> ConvertGltfMaterials(
    const tinygltf::Model& model, std::string_view name,
    std::vector<std::string>* notes);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_MATERIALS_H_
