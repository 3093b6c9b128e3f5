#include "asset/gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "asset/float_range.h"

namespace meshwave {
namespace {

bool IsFiniteNumber(const tinygltf::Value& v) {
  return v.IsNumber() && FitsFloat(v.GetNumberAsDouble());
}

// A number array of exactly `n` finite entries.
bool NumberArray(const tinygltf::Value& v, size_t n, double* out) {
  if (!v.IsArray() || v.ArrayLen() != n) return false;
  for (size_t i = 0; i < n; ++i) {
    const tinygltf::Value& e = v.Get(static_cast<int>(i));
    if (!IsFiniteNumber(e)) return false;
    out[i] = e.GetNumberAsDouble();
  }
  return true;
}

WrapMode WrapFromGltf(int wrap) {
  switch (wrap) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return WrapMode::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return WrapMode::kMirroredRepeat;
    default:
      return WrapMode::kRepeat;
  }
}

class MaterialConverter {
 public:
  MaterialConverter(const tinygltf::Model& model, std::string_view name,
                    std::vector<std::string>* notes)
      : model_(model), name_(name), notes_(notes) {}

  Result<std::vector<Material>> Convert() {
    std::vector<Material> out;
    out.reserve(model_.materials.size());
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      MW_ASSIGN_OR_RETURN(Material m, ConvertOne(i));
      out.push_back(std::move(m));
    }
    for (const tinygltf::Sampler& s : model_.samplers) {
      if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
          s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
          s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
          s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR) {
        Note(
            "NEAREST texture filtering not carried (textures are filtered "
            "linearly)");
        break;
      }
    }
    return out;
  }

 private:
  void Note(const std::string& text) {
    if (noted_.insert(text).second)
      notes_->push_back(std::string(name_) + ": " + text);
  }

  std::string MaterialName(size_t index) const {
    const std::string& n = model_.materials[index].name;
    return "material " + std::to_string(index) +
           (n.empty() ? "" : " \"" + n.substr(0, 60) + "\"");
  }

  Status Error(const std::string& what) const {
    return ParseError(std::string(name_) + ": " + what);
  }

  // The slot of one TextureInfo-like object; `where`: "material 0 \"Car\"
  // baseColorTexture".
  Result<TextureRef> Slot(int texture_index, int tex_coord,
                          const tinygltf::ExtensionMap& extensions,
                          const std::string& where) {
    TextureRef ref;
    if (texture_index < 0) return ref;
    if (static_cast<size_t>(texture_index) >= model_.textures.size()) {
      return Error(where + " refers to texture " +
                   std::to_string(texture_index) + ", the file has " +
                   std::to_string(model_.textures.size()));
    }
    const auto transform = extensions.find("KHR_texture_transform");
    if (transform != extensions.end() && transform->second.IsObject()) {
      const tinygltf::Value& t = transform->second;
      if (t.Has("texCoord")) {
        const tinygltf::Value& c = t.Get("texCoord");
        if (!IsFiniteNumber(c))
          return Error(where + ": texCoord is not a number");
        tex_coord =
            static_cast<int>(std::clamp(c.GetNumberAsDouble(), -1.0, 99.0));
      }
      double offset[2] = {0.0, 0.0};
      double scale[2] = {1.0, 1.0};
      double rotation = 0.0;
      if ((t.Has("offset") && !NumberArray(t.Get("offset"), 2, offset)) ||
          (t.Has("scale") && !NumberArray(t.Get("scale"), 2, scale)) ||
          (t.Has("rotation") && !IsFiniteNumber(t.Get("rotation")))) {
        return Error(
            where +
            ": KHR_texture_transform needs finite numbers (float range: offset "
            "[2], rotation, scale [2])");
      }
      if (t.Has("rotation")) rotation = t.Get("rotation").GetNumberAsDouble();
      // KHR_texture_transform: uv' = T * R * S * uv, with
      // R = [cos sin; -sin cos].
      const double c = std::cos(rotation);
      const double s = std::sin(rotation);
      ref.transform << static_cast<float>(c * scale[0]),
          static_cast<float>(s * scale[1]), static_cast<float>(offset[0]),
          static_cast<float>(-s * scale[0]), static_cast<float>(c * scale[1]),
          static_cast<float>(offset[1]);
    }
    if (tex_coord != 0) {
      Note(where + " reads TEXCOORD_" + std::to_string(tex_coord) +
           ", which is not carried: the texture is dropped from the material");
      return TextureRef{};
    }
    const tinygltf::Texture& texture =
        model_.textures[static_cast<size_t>(texture_index)];
    int source = texture.source;
    const auto webp = texture.extensions.find("EXT_texture_webp");
    if (webp != texture.extensions.end() && webp->second.IsObject() &&
        IsFiniteNumber(webp->second.Get("source"))) {
      source = static_cast<int>(std::clamp(
          webp->second.Get("source").GetNumberAsDouble(), -1.0, 1e9));
    }
    if (source < 0) {
      Note(where + ": texture " + std::to_string(texture_index) +
           " has no PNG, JPEG or WebP source (KTX2 is not decoded): the "
           "texture is dropped from the material");
      return TextureRef{};
    }
    if (static_cast<size_t>(source) >= model_.images.size()) {
      return Error("texture " + std::to_string(texture_index) +
                   " refers to image " + std::to_string(source) +
                   ", the file has " + std::to_string(model_.images.size()));
    }
    ref.image = source;
    if (texture.sampler >= 0) {
      if (static_cast<size_t>(texture.sampler) >= model_.samplers.size()) {
        return Error("texture " + std::to_string(texture_index) +
                     " refers to sampler " + std::to_string(texture.sampler) +
                     ", the file has " +
                     std::to_string(model_.samplers.size()));
      }
      const tinygltf::Sampler& s =
          model_.samplers[static_cast<size_t>(texture.sampler)];
      ref.wrap_u = WrapFromGltf(s.wrapS);
      ref.wrap_v = WrapFromGltf(s.wrapT);
    }
    return ref;
  }

  Result<Material> ConvertOne(size_t index) {
    const tinygltf::Material& g = model_.materials[index];
    const std::string who = MaterialName(index);
    Material m;
    m.name = g.name;
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    auto finite = [](double v) { return FitsFloat(v); };
    if (pbr.baseColorFactor.size() != 4 || !finite(pbr.baseColorFactor[0]) ||
        !finite(pbr.baseColorFactor[1]) || !finite(pbr.baseColorFactor[2]) ||
        !finite(pbr.baseColorFactor[3])) {
      return Error(who + ": baseColorFactor needs 4 finite numbers");
    }
    for (int k = 0; k < 4; ++k) {
      m.base_color_factor[k] = static_cast<float>(pbr.baseColorFactor[k]);
    }
    if (!finite(pbr.metallicFactor) || !finite(pbr.roughnessFactor) ||
        !finite(g.normalTexture.scale) ||
        !finite(g.occlusionTexture.strength) || !finite(g.alphaCutoff)) {
      return Error(who + ": a factor is not a finite number in float range");
    }
    m.metallic_factor = static_cast<float>(pbr.metallicFactor);
    m.roughness_factor = static_cast<float>(pbr.roughnessFactor);
    m.normal_scale = static_cast<float>(g.normalTexture.scale);
    m.occlusion_strength = static_cast<float>(g.occlusionTexture.strength);
    m.alpha_cutoff = static_cast<float>(g.alphaCutoff);
    if (!g.emissiveFactor.empty()) {
      if (g.emissiveFactor.size() != 3 || !finite(g.emissiveFactor[0]) ||
          !finite(g.emissiveFactor[1]) || !finite(g.emissiveFactor[2])) {
        return Error(who + ": emissiveFactor needs 3 finite numbers");
      }
      for (int k = 0; k < 3; ++k) {
        m.emissive_factor[k] = static_cast<float>(g.emissiveFactor[k]);
      }
    }
    if (g.alphaMode == "MASK") {
      m.alpha_mode = AlphaMode::kMask;
    } else if (g.alphaMode == "BLEND") {
      m.alpha_mode = AlphaMode::kBlend;
    } else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) {
      return Error(who + ": unknown alphaMode \"" + g.alphaMode.substr(0, 20) +
                   "\"");
    }
    m.double_sided = g.doubleSided;
    MW_ASSIGN_OR_RETURN(
        m.base_color_texture,
        Slot(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
             pbr.baseColorTexture.extensions, who + " baseColorTexture"));
    MW_ASSIGN_OR_RETURN(m.metallic_roughness_texture,
                        Slot(pbr.metallicRoughnessTexture.index,
                             pbr.metallicRoughnessTexture.texCoord,
                             pbr.metallicRoughnessTexture.extensions,
                             who + " metallicRoughnessTexture"));
    MW_ASSIGN_OR_RETURN(
        m.normal_texture,
        Slot(g.normalTexture.index, g.normalTexture.texCoord,
             g.normalTexture.extensions, who + " normalTexture"));
    MW_ASSIGN_OR_RETURN(
        m.occlusion_texture,
        Slot(g.occlusionTexture.index, g.occlusionTexture.texCoord,
             g.occlusionTexture.extensions, who + " occlusionTexture"));
    MW_ASSIGN_OR_RETURN(
        m.emissive_texture,
        Slot(g.emissiveTexture.index, g.emissiveTexture.texCoord,
             g.emissiveTexture.extensions, who + " emissiveTexture"));
    return m;
  }

  const tinygltf::Model& model_;
  std::string_view name_;
  std::vector<std::string>* notes_;
  std::set<std::string> noted_;
};

}  // namespace

Result<std::vector<Material>> ConvertGltfMaterials(
    const tinygltf::Model& model, std::string_view name,
    std::vector<std::string>* notes) {
  return MaterialConverter(model, name, notes).Convert();
}

}  // namespace meshwave
