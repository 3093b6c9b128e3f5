#include "asset/gltf_notes.h"

#include <array>
#include <set>
#include <utility>

namespace meshwave {
namespace {

struct KnownExtension {
  std::string_view name;
  std::string_view lost;  // what the asset loses; empty: carried
};

// Extensions of the Khronos registry (and common vendor ones) with what
// dropping them loses. Anything else is named without an explanation.
constexpr std::array<KnownExtension, 27> kExtensions = {{
    {"KHR_texture_transform", ""},
    {"KHR_mesh_quantization", ""},
    {"EXT_texture_webp", ""},
    {"KHR_draco_mesh_compression",
     "Draco-compressed primitives not decoded; their uncompressed fallback "
     "data was read"},
    {"EXT_meshopt_compression",
     "meshopt-compressed buffer views not decoded; their uncompressed "
     "fallback data was read"},
    {"KHR_materials_clearcoat", "the clearcoat layer"},
    {"KHR_materials_transmission", "transmission (glass-like see-through)"},
    {"KHR_materials_sheen", "sheen (the cloth-like rim)"},
    {"KHR_materials_iridescence", "iridescence (thin-film colour shift)"},
    {"KHR_materials_volume", "volume (thickness and attenuation)"},
    {"KHR_materials_ior", "the index of refraction"},
    {"KHR_materials_specular", "specular strength and colour"},
    {"KHR_materials_emissive_strength",
     "emissive strength (emission is read at strength 1)"},
    {"KHR_materials_unlit", "unlit shading (the material is read as lit)"},
    {"KHR_materials_anisotropy", "anisotropy"},
    {"KHR_materials_dispersion", "dispersion"},
    {"KHR_materials_diffuse_transmission", "diffuse transmission"},
    {"KHR_materials_variants",
     "material variants (the default materials are read)"},
    {"KHR_materials_pbrSpecularGlossiness",
     "the specular-glossiness material (its metallic-roughness fallback is "
     "read)"},
    {"KHR_lights_punctual", "lights"},
    {"KHR_texture_basisu",
     "KTX2/Basis textures (their PNG/JPEG/WebP fallbacks are read where "
     "present)"},
    {"KHR_animation_pointer", "animation of properties"},
    {"KHR_xmp_json_ld", "XMP metadata"},
    {"KHR_xmp", "XMP metadata"},
    {"EXT_mesh_gpu_instancing",
     "GPU instancing (each mesh is read once, at its node)"},
    {"EXT_lights_image_based", "image-based lights"},
    {"MSFT_lod", "levels of detail (the finest is read)"},
}};

std::string Plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

void AddGltfDocumentNotes(const tinygltf::Model& model, std::string_view name,
                          std::vector<std::string>* notes) {
  const std::string prefix = std::string(name) + ": ";
  std::set<std::string> seen;
  for (const std::string& used : model.extensionsUsed) {
    if (!seen.insert(used).second) continue;
    const std::string shown = used.substr(0, 60);
    std::string_view lost = "its data";
    bool carried = false;
    for (const KnownExtension& e : kExtensions) {
      if (e.name == used) {
        lost = e.lost;
        carried = e.lost.empty();
      }
    }
    if (carried) continue;
    notes->push_back(prefix + shown + " not carried: " + std::string(lost));
  }
  if (!model.skins.empty()) {
    notes->push_back(prefix + Plural(model.skins.size(), "skin", "skins") +
                     " not carried: the meshes are read in their bind pose");
  }
  if (!model.animations.empty()) {
    notes->push_back(
        prefix + Plural(model.animations.size(), "animation", "animations") +
        " not carried");
  }
  if (!model.cameras.empty()) {
    notes->push_back(prefix +
                     Plural(model.cameras.size(), "camera", "cameras") +
                     " not carried");
  }
}

}  // namespace meshwave
