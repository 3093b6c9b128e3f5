// What every MeshAsset a reader returns must satisfy (meshwave/mesh_asset.h),
// checked by the asset fuzz targets: indices in range, attribute faces one
// per mesh face, finite values, texture slots naming existing images,
// decoded images of the size they say.
#ifndef MESHWAVE_TESTS_FUZZ_ASSET_INVARIANTS_TESTONLY_H_
#define MESHWAVE_TESTS_FUZZ_ASSET_INVARIANTS_TESTONLY_H_

#include <string>
#include <string_view>
#include <vector>

#include "fuzz_require_testonly.h"
#include "meshwave/mesh_asset.h"

namespace meshwave::fuzz {

// Splits `input` at every `separator` (the fuzz targets' multi-file inputs).
inline std::vector<std::string_view> SplitFiles(std::string_view input,
                                                std::string_view separator) {
  std::vector<std::string_view> out;
  while (true) {
    const size_t at = input.find(separator);
    out.push_back(input.substr(0, at));
    if (at == std::string_view::npos) return out;
    input.remove_prefix(at + separator.size());
  }
}

// Limits small enough for fuzzing speed and the 2 GiB RSS cap.
inline AssetLimits FuzzLimits() {
  AssetLimits limits;
  limits.max_file_bytes = 1 << 24;
  limits.max_image_pixels = 1 << 20;
  limits.max_image_bytes = 1 << 24;
  limits.max_triangles = 1 << 18;
  limits.max_vertices = 1 << 18;
  limits.max_json_bytes = 1 << 20;
  return limits;
}

template <class T>
void RequireAttribute(const CornerAttribute<T>& a, size_t faces,
                      const char* what) {
  if (a.faces.empty()) {
    Require(a.values.empty(), what);
    return;
  }
  Require(a.faces.size() == faces, what);
  for (const Face& f : a.faces) {
    for (uint32_t i : f) Require(i < a.values.size(), what);
  }
  for (const T& v : a.values) Require(v.allFinite(), what);
}

inline void RequireValidAsset(const MeshAsset& asset) {
  const TriMesh& mesh = asset.mesh;
  Require(!mesh.faces.empty(), "an asset has faces");
  for (const Vec3& p : mesh.positions)
    Require(p.allFinite(), "positions are finite");
  for (const Face& f : mesh.faces) {
    for (uint32_t v : f)
      Require(v < mesh.positions.size(), "face indices are in range");
  }
  RequireAttribute(asset.uv, mesh.faces.size(), "uv faces match the mesh");
  RequireAttribute(asset.color, mesh.faces.size(),
                   "colour faces match the mesh");
  for (const auto& c : asset.color.values) {
    Require((c.array() >= 0.0f).all() && (c.array() <= 1.0f).all(),
            "colours in [0, 1]");
  }
  Require(asset.face_material.empty() ||
              asset.face_material.size() == mesh.faces.size(),
          "one material per face");
  for (uint32_t m : asset.face_material) {
    Require(m < asset.materials.size(), "face materials exist");
  }
  for (const Material& m : asset.materials) {
    for (const TextureRef* t :
         {&m.base_color_texture, &m.metallic_roughness_texture,
          &m.normal_texture, &m.occlusion_texture, &m.emissive_texture}) {
      Require(
          t->image >= -1 && t->image < static_cast<int>(asset.images.size()),
          "texture slots name existing images");
      Require(!t->present() || !asset.images[t->image].rgba.empty(),
              "images of carried slots are decoded");
    }
  }
  for (const AssetImage& image : asset.images) {
    Require(image.rgba.empty() ||
                image.rgba.size() == size_t{image.width} * image.height * 4,
            "decoded images hold width * height * 4 bytes");
  }
}

}  // namespace meshwave::fuzz

#endif  // MESHWAVE_TESTS_FUZZ_ASSET_INVARIANTS_TESTONLY_H_
