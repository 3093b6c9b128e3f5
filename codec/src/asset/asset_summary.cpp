// DescribeMeshAsset: one paragraph for `meshwave info`.
#include <string>
#include <vector>

#include "meshwave/mesh_asset.h"

namespace meshwave {
namespace {

std::string Count(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string MimeShort(const std::string& mime) {
  if (mime == "image/png") return "PNG";
  if (mime == "image/jpeg") return "JPEG";
  if (mime == "image/webp") return "WebP";
  return "undecoded";
}

// "base colour, normal and occlusion textures", or "no textures".
std::string Slots(const Material& m) {
  std::vector<const char*> names;
  if (m.base_color_texture.present()) names.push_back("base colour");
  if (m.metallic_roughness_texture.present())
    names.push_back("metallic-roughness");
  if (m.normal_texture.present()) names.push_back("normal");
  if (m.occlusion_texture.present()) names.push_back("occlusion");
  if (m.emissive_texture.present()) names.push_back("emissive");
  if (names.empty()) return "no textures";
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out + (names.size() == 1 ? " texture" : " textures");
}

}  // namespace

std::string DescribeMeshAsset(const MeshAsset& asset) {
  std::string out;
  out += asset.uv.empty()
             ? "no UVs"
             : "UVs (" + Count(asset.uv.values.size(), "value", "values") + ")";
  out += ", ";
  out += asset.color.empty()
             ? "no vertex colours"
             : "vertex colours (" +
                   Count(asset.color.values.size(), "value", "values") + ")";
  out += "; " + Count(asset.materials.size(), "material", "materials");
  for (size_t i = 0; i < asset.materials.size(); ++i) {
    const Material& m = asset.materials[i];
    out += (i == 0 ? ": \"" : ", \"") + m.name.substr(0, 60) + "\" (" +
           Slots(m) + ")";
  }
  out += "; " + Count(asset.images.size(), "image", "images");
  for (size_t i = 0; i < asset.images.size(); ++i) {
    const AssetImage& image = asset.images[i];
    out +=
        (i == 0 ? ": " : ", ") + image.name + " " + MimeShort(image.mime_type);
    if (!image.rgba.empty()) {
      // Appended piece by piece: GCC 12's -Wrestrict misfires on
      // `" " + std::to_string(...)` at -O3 outside a unity build.
      out += ' ';
      out += std::to_string(image.width);
      out += 'x';
      out += std::to_string(image.height);
    }
  }
  out += ".";
  if (asset.notes.empty()) {
    out += " Nothing in the file was left out.";
  } else {
    out += " Notes: ";
    for (size_t i = 0; i < asset.notes.size(); ++i) {
      out += (i == 0 ? "" : "; ") + asset.notes[i];
    }
    out += ".";
  }
  return out;
}

}  // namespace meshwave
