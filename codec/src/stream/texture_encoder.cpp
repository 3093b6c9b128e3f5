#include "stream/texture_encoder.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "meshwave/stream_limits.h"
#include "texture/atlas_layout.h"
#include "texture/image_size.h"

namespace meshwave {
namespace {

proto::TextureRole ToProto(TextureRole role) {
  return static_cast<proto::TextureRole>(static_cast<int>(role));
}

// Per base face of the stream, 3 t + r: the input's base face t whose
// triangle it owns, its corner i on t's corner (i + r) mod 3. Empty when
// every face kept its place and rotation (the field is then left out).
Result<std::vector<uint32_t>> FaceTriangles(const SemiRegularMesh& input,
                                            const SemiRegularMesh& stream,
                                            const std::vector<uint32_t>& input_vertex) {
  const std::vector<Face>& before = input.hierarchy->faces(0);
  const std::vector<Face>& after = stream.hierarchy->faces(0);
  // Each input face by its vertices rotated to put the smallest first.
  auto key = [](const Face& f) {
    const int first = static_cast<int>(std::min_element(f.begin(), f.end()) - f.begin());
    return std::array<uint32_t, 3>{f[first], f[(first + 1) % 3], f[(first + 2) % 3]};
  };
  std::map<std::array<uint32_t, 3>, uint32_t> face_of;
  for (uint32_t t = 0; t < before.size(); ++t) face_of[key(before[t])] = t;
  std::vector<uint32_t> out(after.size());
  bool identity = true;
  for (uint32_t f = 0; f < after.size(); ++f) {
    Face old;
    for (int i = 0; i < 3; ++i) old[i] = input_vertex[after[f][i]];
    const auto found = face_of.find(key(old));
    if (found == face_of.end()) {
      return InvalidArgument("texture: stream base face " + std::to_string(f) +
                      " is no face of the input's base");
    }
    const uint32_t t = found->second;
    uint32_t r = 0;
    while (r < 3 && before[t][r] != old[0]) ++r;
    out[f] = 3 * t + r;
    identity = identity && t == f && r == 0;
  }
  if (identity) out.clear();
  return out;
}

}  // namespace

Result<EncodedTexture> EncodeTexture(const BakedTexture& texture, const SemiRegularMesh& input,
                                     const SemiRegularMesh& stream,
                                     const std::vector<uint32_t>& input_vertex,
                                     uint32_t first_packet, const EncodeOptions& options) {
  const auto base_faces = static_cast<uint32_t>(input.hierarchy->faces(0).size());
  const TextureAtlas& a = texture.atlas;
  auto created = AtlasLayout::Create(base_faces, a.cell, a.gutter, a.columns);
  if (!created.ok()) return created.status().WithContext("texture");
  const AtlasLayout& atlas = *created;
  const TextureMaterial& material = texture.material;
  const float scalars[] = {material.metallic_factor, material.roughness_factor,
                           material.normal_scale, material.occlusion_strength};
  bool finite = material.emissive_factor.allFinite();
  for (float v : scalars) finite = finite && std::isfinite(v);
  if (!finite) return InvalidArgument("texture: a material scalar is not finite");
  if (!(options.texture_rd_weight > 0) || !std::isfinite(options.texture_rd_weight)) {
    return InvalidArgument("the texture's rd weight must be finite and positive");
  }
  if (texture.maps.empty() || texture.maps.size() > kMaxTextureMaps) {
    return InvalidArgument("texture: " + std::to_string(texture.maps.size()) +
                           " maps (1 to " + std::to_string(kMaxTextureMaps) + ", one per role)");
  }
  EncodedTexture out;
  proto::Texture& header = out.header;
  header.set_cell(atlas.cell());
  header.set_gutter(atlas.gutter());
  header.set_columns(atlas.columns());
  MW_ASSIGN_OR_RETURN(std::vector<uint32_t> triangles, FaceTriangles(input, stream, input_vertex));
  for (uint32_t t : triangles) header.add_face_triangles(t);
  header.set_metallic_factor(material.metallic_factor);
  header.set_roughness_factor(material.roughness_factor);
  for (int c = 0; c < 3; ++c) header.add_emissive_factor(material.emissive_factor[c]);
  header.set_normal_scale(material.normal_scale);
  header.set_occlusion_strength(material.occlusion_strength);
  header.set_alpha_blend(material.alpha_blend);
  header.set_double_sided(material.double_sided);
  header.set_rd_weight(options.texture_rd_weight);
  // The distortion model (FORMAT.md 7): a map with no level held counts
  // 1/12 per vertex of the finest level (the squared error, peak 1, of
  // values uniform in [0, 1] shown as their mean), and each level halves
  // the error of the one before. A model, not a measurement: it ranks a
  // map's levels against the geometry's packets by their bytes.
  const double start =
      static_cast<double>(input.hierarchy->vertex_count(input.hierarchy->levels())) / 12;
  uint32_t id = first_packet;
  for (size_t m = 0; m < texture.maps.size(); ++m) {
    const TextureMap& map = texture.maps[m];
    const std::string owner = "texture map " + std::to_string(m) + " (" +
                              std::string(TextureRoleName(map.role)) + "): ";
    if (static_cast<int>(map.role) > static_cast<int>(TextureRole::kEmissive)) {
      return InvalidArgument(owner + "unknown role " + std::to_string(static_cast<int>(map.role)));
    }
    for (size_t other = 0; other < m; ++other) {
      if (texture.maps[other].role == map.role) {
        return InvalidArgument(owner + "a second map of its role");
      }
    }
    const size_t levels = map.levels.size();
    if (levels == 0 || levels > kMaxTextureLevels) {
      return InvalidArgument(owner + std::to_string(levels) + " levels (1 to " +
                             std::to_string(kMaxTextureLevels) + ")");
    }
    bool known = false;
    for (const char* mime : kTextureMimeTypes) known = known || map.mime_type == mime;
    if (!known) {
      return InvalidArgument(owner + "image type \"" + map.mime_type +
                             "\" (image/jpeg, image/png or image/webp)");
    }
    proto::TextureMap& out_map = *header.add_maps();
    out_map.set_role(ToProto(map.role));
    out_map.set_mime_type(map.mime_type);
    out.chain_start.push_back(start);
    double error = start;
    for (size_t k = 0; k < levels; ++k) {
      const uint32_t shift = static_cast<uint32_t>(levels - 1 - k);
      const uint32_t divisor = 1u << shift;
      if (atlas.width() % divisor != 0 || atlas.height() % divisor != 0) {
        return InvalidArgument(owner + std::to_string(levels) + " levels of an atlas of " +
                               std::to_string(atlas.width()) + " x " +
                               std::to_string(atlas.height()) +
                               " texels, which does not halve " + std::to_string(shift) +
                               " times");
      }
      const ImageSize want{atlas.width() / divisor, atlas.height() / divisor};
      const std::string& bytes = map.levels[k];
      const std::string level_name = owner + "level " + std::to_string(k);
      auto size = ReadImageSize(bytes, map.mime_type);
      if (!size.ok()) return size.status().WithContext(level_name);
      if (size->width != want.width || size->height != want.height) {
        return InvalidArgument(level_name + " is " + std::to_string(size->width) + " x " +
                               std::to_string(size->height) + " pixels, not " +
                               std::to_string(want.width) + " x " +
                               std::to_string(want.height) + " (the atlas's size / 2^" +
                               std::to_string(shift) + ")");
      }
      if (bytes.size() > (1u << 30)) return InvalidArgument(level_name + " exceeds 1 GiB");
      proto::TextureLevel& level = *out_map.add_levels();
      level.set_packet(id++);
      level.set_width(want.width);
      level.set_height(want.height);
      out.packets.push_back(bytes);
      out.reduction.push_back(error / 2);
      error /= 2;
    }
  }
  return out;
}

}  // namespace meshwave
