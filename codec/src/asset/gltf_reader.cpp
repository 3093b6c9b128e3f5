// ParseGltfAsset: the glTF reader's stages in order (gltf_loader: bytes to
// tinygltf's Model; gltf_scene: geometry and per-corner attributes;
// gltf_materials: materials; then the images, decoded with limits).
#include <utility>

#include "asset/asset_image.h"
#include "asset/asset_readers.h"
#include "asset/gltf_gate.h"
#include "asset/gltf_loader.h"
#include "asset/gltf_materials.h"
#include "asset/gltf_notes.h"
#include "asset/gltf_scene.h"
#include "asset/weld.h"

namespace meshwave {
namespace {

std::string ImageName(const tinygltf::Image& image, size_t index) {
  std::string out = "image " + std::to_string(index);
  if (!image.name.empty()) out += " \"" + image.name.substr(0, 60) + "\"";
  return out;
}

// The encoded bytes of every glTF image: kept by the loader (bufferView,
// data URI) or read here from the file set (a relative URI).
Status LoadImages(const tinygltf::Model& model, FileSet& files,
                  std::string_view main_name, const AssetLimits& limits,
                  const std::vector<bool>& used, MeshAsset& asset) {
  uint64_t decoded_left = limits.max_image_bytes;
  asset.images.resize(model.images.size());
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& g = model.images[i];
    AssetImage& image = asset.images[i];
    if (!g.image.empty()) {
      image.name = std::string(main_name) + " " + ImageName(g, i);
      image.encoded.assign(g.image.begin(), g.image.end());
    } else {
      Result<std::string> resolved =
          ResolveFileSetReference(main_name, DecodeUriPath(g.uri));
      if (!resolved.ok()) {
        return resolved.status().WithContext(std::string(main_name) + ": " +
                                             ImageName(g, i));
      }
      image.name = std::move(resolved).value();
      Result<std::string_view> bytes = files.Read(image.name);
      if (!bytes.ok()) {
        return bytes.status().WithContext(std::string(main_name) + ": " +
                                          ImageName(g, i) + " is missing");
      }
      image.encoded.assign(bytes->begin(), bytes->end());
    }
    const Status decoded = DecodeAssetImage(image, limits, &decoded_left);
    if (decoded.ok()) continue;
    if (used[i]) return decoded;
    asset.notes.push_back(decoded.message() +
                          " (used by no carried texture slot: kept undecoded)");
  }
  return Status::Ok();
}

}  // namespace

Result<MeshAsset> ParseGltfAsset(std::string_view bytes, FileSet& files,
                                 std::string_view main_name,
                                 const AssetLimits& limits,
                                 const GltfReadOptions& options) {
  std::vector<std::string> warnings;
  MW_ASSIGN_OR_RETURN(
      const tinygltf::Model model,
      LoadGltfModel(bytes, files, main_name, limits, &warnings));
  MeshAsset asset;
  AddGltfDocumentNotes(model, main_name, &asset.notes);
  MW_ASSIGN_OR_RETURN(GltfGeometry geometry,
                      BuildGltfGeometry(model, main_name, limits));
  MW_ASSIGN_OR_RETURN(asset.materials,
                      ConvertGltfMaterials(model, main_name, &asset.notes));
  asset.notes.insert(asset.notes.end(), geometry.notes.begin(),
                     geometry.notes.end());
  asset.notes.insert(asset.notes.end(), warnings.begin(), warnings.end());
  asset.mesh = std::move(geometry.mesh);
  asset.uv = std::move(geometry.uv);
  asset.color = std::move(geometry.color);
  // Faces without a material get glTF's default one, appended.
  bool any_material = false;
  bool any_default = false;
  for (int32_t m : geometry.face_material) {
    (m >= 0 ? any_material : any_default) = true;
  }
  if (any_material) {
    const uint32_t fallback = static_cast<uint32_t>(asset.materials.size());
    asset.face_material.reserve(geometry.face_material.size());
    for (int32_t m : geometry.face_material) {
      asset.face_material.push_back(m >= 0 ? static_cast<uint32_t>(m)
                                           : fallback);
    }
    if (any_default) {
      Material standard;
      standard.name = "default";
      asset.materials.push_back(standard);
    }
  }
  if (asset.mesh.faces.empty()) {
    return ParseError(std::string(main_name) +
                      ": the scene draws no triangles");
  }
  WeldPositions(asset.mesh);
  if (options.load_images) {
    std::vector<bool> used(model.images.size(), false);
    for (const Material& m : asset.materials) {
      for (const TextureRef* t :
           {&m.base_color_texture, &m.metallic_roughness_texture,
            &m.normal_texture, &m.occlusion_texture, &m.emissive_texture}) {
        if (t->present()) used[static_cast<size_t>(t->image)] = true;
      }
    }
    MW_RETURN_IF_ERROR(
        LoadImages(model, files, main_name, limits, used, asset));
  }
  return asset;
}

}  // namespace meshwave
