// The notes about a whole glTF document: extensions the data model does not
// carry (each named with what it would have added), skins, animations,
// cameras. Notes about what a primitive or material dropped come from
// gltf_scene.cpp and gltf_materials.cpp.
#ifndef MESHWAVE_ASSET_GLTF_NOTES_H_
#define MESHWAVE_ASSET_GLTF_NOTES_H_

#include <string>
#include <string_view>
#include <vector>

#include "asset/tiny_gltf_config.h"

namespace meshwave {

void AddGltfDocumentNotes(const tinygltf::Model& model, std::string_view name,
                          std::vector<std::string>* notes);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_NOTES_H_
