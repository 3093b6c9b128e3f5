#include "stream/decoder_setup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/quoted.h"
#include "meshwave/stream_limits.h"
#include "meshwave/texture.h"
#include "original/original_positions.h"
#include "stream/packet_index.h"
#include "texture/atlas_layout.h"
#include "quant/deadzone_quantizer.h"
#include "stream/sawt_field_decoder.h"
#include "stream/stream_format.h"

namespace meshwave {

Status ValidateVersionAndLevels(const StreamHeader& h) {
  MW_RETURN_IF_ERROR(CheckFormatVersion(h).WithContext("stream"));
  const uint32_t levels = h.transform.levels;
  if (levels > kMaxStreamLevels) {
    return ParseError("header: " + std::to_string(levels) + " levels (at most " +
                      std::to_string(kMaxStreamLevels) + ")");
  }
  return Status::Ok();
}

namespace {

// `owner` names whose quantizers these are in messages ("" for the
// geometry's).
Status CheckQuantizers(const std::vector<StreamHeader::Quantizer>& quantizers, uint32_t levels,
                       const std::string& owner) {
  if (quantizers.size() != 3 * static_cast<size_t>(levels)) {
    return ParseError("header: " + owner + std::to_string(quantizers.size()) +
                      " quantizers for " + std::to_string(levels) + " subbands");
  }
  for (const auto& q : quantizers) {
    if (!(q.step > 0) || !std::isfinite(q.step) || q.deadzone > 3 || q.top_bitplane < -1 ||
        q.top_bitplane > kMaxBitplane) {
      return ParseError("header: " + owner + "a quantizer is out of range");
    }
  }
  return Status::Ok();
}

}  // namespace

Status ValidateQuantizers(const StreamHeader& h) {
  return CheckQuantizers(h.quantizers, h.transform.levels, "");
}

Status ValidateChannels(const StreamHeader& h) {
  if (h.channels.size() > kMaxChannels) {
    return ParseError("header: " + std::to_string(h.channels.size()) + " channels (at most " +
                      std::to_string(kMaxChannels) + ", one of each kind)");
  }
  for (size_t k = 0; k < h.channels.size(); ++k) {
    const StreamHeader::Channel& channel = h.channels[k];
    const std::string owner = "channel " + std::to_string(k) + ": ";
    if (channel.kind != StreamChannelKind::kColor) {
      return ParseError("header: " + owner + "unknown kind " +
                        std::to_string(static_cast<int32_t>(channel.kind)) +
                        " (this build knows 1, colour)");
    }
    for (size_t other = 0; other < k; ++other) {
      if (h.channels[other].kind == channel.kind) {
        return ParseError("header: " + owner + "a second channel of the same kind");
      }
    }
    MW_RETURN_IF_ERROR(CheckQuantizers(channel.quantizers, h.transform.levels, owner));
    if (!(channel.base_step > 0) || !std::isfinite(channel.base_step)) {
      return ParseError("header: " + owner + "base step not finite and positive");
    }
    if (!(channel.rd_weight > 0) || !std::isfinite(channel.rd_weight)) {
      return ParseError("header: " + owner + "rd weight not finite and positive");
    }
    // 3 varints of 1 to 5 bytes per base vertex (DecodeChannelBase reads
    // them once the base mesh is decoded).
    const uint64_t values = 3 * uint64_t{h.base.vertex_count};
    if (channel.base.size() < values || channel.base.size() > 5 * values) {
      return ParseError("header: " + owner + std::to_string(channel.base.size()) +
                        " bytes of base values for " + std::to_string(h.base.vertex_count) +
                        " base vertices (3 varints each)");
    }
  }
  return Status::Ok();
}

Status ValidateTexture(const StreamHeader& h) {
  if (!h.texture) return Status::Ok();
  const StreamHeader::Texture& t = *h.texture;
  const uint32_t faces = h.base.face_count;
  if (t.columns == 0) return ParseError("header: texture: the atlas has 0 columns");
  auto atlas = AtlasLayout::Create(faces, t.cell, t.gutter, t.columns);
  if (!atlas.ok()) return ParseError("header: texture: " + atlas.status().message());
  if (!t.face_triangles.empty()) {
    if (t.face_triangles.size() != faces) {
      return ParseError("header: texture: " + std::to_string(t.face_triangles.size()) +
                        " face triangles for " + std::to_string(faces) + " base faces");
    }
    std::vector<char> used(faces, 0);
    for (uint32_t f = 0; f < faces; ++f) {
      const uint32_t triangle = t.face_triangles[f] / 3;
      if (triangle >= faces || used[triangle]) {
        return ParseError("header: texture: base face " + std::to_string(f) + " names triangle " +
                          std::to_string(triangle) +
                          (triangle >= faces ? " (out of range)" : " (named twice)"));
      }
      used[triangle] = 1;
    }
  }
  const float scalars[] = {t.metallic_factor, t.roughness_factor, t.normal_scale,
                           t.occlusion_strength};
  bool finite = t.emissive_factor.size() == 3;
  for (float v : scalars) finite = finite && std::isfinite(v);
  for (float v : t.emissive_factor) finite = finite && std::isfinite(v);
  if (!finite) {
    return ParseError("header: texture: a material scalar is not finite (or not 3 emissive "
                      "factors)");
  }
  if (!(t.rd_weight > 0) || !std::isfinite(t.rd_weight)) {
    return ParseError("header: texture: rd weight not finite and positive");
  }
  if (t.maps.empty() || t.maps.size() > kMaxTextureMaps) {
    return ParseError("header: texture: " + std::to_string(t.maps.size()) + " maps (1 to " +
                      std::to_string(kMaxTextureMaps) + ")");
  }
  // Texture packets follow every other packet (FORMAT.md 2.1).
  PacketLayout layout(h);
  uint32_t id = static_cast<uint32_t>(layout.count());
  for (const StreamHeader::Texture::Map& map : t.maps) id -= static_cast<uint32_t>(
      std::min<size_t>(map.levels.size(), kMaxTextureLevels));
  for (size_t m = 0; m < t.maps.size(); ++m) {
    const StreamHeader::Texture::Map& map = t.maps[m];
    const std::string owner = "header: texture map " + std::to_string(m) + ": ";
    if (map.role < 0 || map.role > static_cast<int32_t>(TextureRole::kEmissive)) {
      return ParseError(owner + "unknown role " + std::to_string(map.role));
    }
    for (size_t other = 0; other < m; ++other) {
      if (t.maps[other].role == map.role) return ParseError(owner + "a second map of its role");
    }
    bool known = false;
    for (const char* mime : kTextureMimeTypes) known = known || map.mime_type == mime;
    if (!known) {
      return ParseError(owner + "image type " + Quoted(map.mime_type) +
                        " (image/jpeg, image/png or image/webp)");
    }
    const size_t levels = map.levels.size();
    if (levels == 0 || levels > kMaxTextureLevels) {
      return ParseError(owner + std::to_string(levels) + " levels (1 to " +
                        std::to_string(kMaxTextureLevels) + ")");
    }
    const uint32_t width = atlas->width(), height = atlas->height();
    for (size_t k = 0; k < levels; ++k) {
      const StreamHeader::Texture::Level& level = map.levels[k];
      const uint32_t shift = static_cast<uint32_t>(levels - 1 - k);
      const uint32_t divisor = 1u << shift;
      if (width % divisor != 0 || height % divisor != 0) {
        return ParseError(owner + "the atlas of " + std::to_string(width) + " x " +
                          std::to_string(height) + " texels does not halve " +
                          std::to_string(shift) + " times");
      }
      if (level.width != width / divisor || level.height != height / divisor) {
        return ParseError(owner + "level " + std::to_string(k) + " is " +
                          std::to_string(level.width) + " x " + std::to_string(level.height) +
                          ", not " + std::to_string(width / divisor) + " x " +
                          std::to_string(height / divisor) + " (the atlas's size / 2^" +
                          std::to_string(shift) + ")");
      }
      if (level.packet != id) {
        return ParseError(owner + "level " + std::to_string(k) + " names packet " +
                          std::to_string(level.packet) + ", not " + std::to_string(id));
      }
      ++id;
    }
  }
  return Status::Ok();
}

Status ValidateOriginal(const StreamHeader& h) {
  if (!h.original) return Status::Ok();
  const StreamHeader::Original& o = *h.original;
  if (o.vertex_count == 0 || o.vertex_count > kMaxOriginalVertices) {
    return ParseError("header: original layer: " + std::to_string(o.vertex_count) +
                      " vertices (1 to " + std::to_string(kMaxOriginalVertices) + ")");
  }
  if (o.face_count > kMaxOriginalFaces) {
    return ParseError("header: original layer: " + std::to_string(o.face_count) +
                      " faces (at most " + std::to_string(kMaxOriginalFaces) + ")");
  }
  bool finite = o.origin.size() == 3 && std::isfinite(o.step) && o.step > 0;
  for (double v : o.origin) finite = finite && std::isfinite(v);
  if (!finite) {
    return ParseError("header: original layer: the grid needs 3 finite origin coordinates and a "
                      "finite positive step");
  }
  if (o.extent > original::kMaxGridCoordinate) {
    return ParseError("header: original layer: grid extent " + std::to_string(o.extent) +
                      " beyond " + std::to_string(original::kMaxGridCoordinate));
  }
  if (o.refinement_planes > kMaxOriginalRefinementPlanes) {
    return ParseError("header: original layer: " + std::to_string(o.refinement_planes) +
                      " refinement planes (at most " +
                      std::to_string(kMaxOriginalRefinementPlanes) + ")");
  }
  return Status::Ok();
}

Result<TransformSettings> SetUpHierarchy(const StreamHeader& header, uint32_t max_base_vertices,
                                         DecodedBase& base,
                                         std::shared_ptr<const SemiRegularHierarchy>& hierarchy) {
  MW_ASSIGN_OR_RETURN(TransformSettings settings, ReadTransformSettings(header.transform));
  MW_ASSIGN_OR_RETURN(base, DecodeBaseMesh(header.base, max_base_vertices));
  const int levels = static_cast<int>(header.transform.levels);
  auto built = SemiRegularHierarchy::Build(static_cast<uint32_t>(base.positions.size()),
                                           base.faces, levels);
  if (!built.ok()) return built.status().WithContext("stream base mesh");
  hierarchy = *built;
  const auto& h = *hierarchy;
  if (header.vertices != h.vertex_count(levels) || header.faces != h.faces(levels).size()) {
    return ParseError("header: vertex or face count does not match the hierarchy");
  }
  if (header.bbox_min.size() != 3 || header.bbox_max.size() != 3) {
    return ParseError("header: bounding box needs 3 coordinates");
  }
  if (settings.predictor == Predictor::kSawt) {
    MW_ASSIGN_OR_RETURN(settings.sawt, DecodeSawtChoices(*header.transform.sawt, h, base.grid));
  }
  return settings;
}

Status SetUpDecoder(const StreamHeader& header, uint32_t max_base_vertices, DecodedBase& base,
                    std::shared_ptr<const SemiRegularHierarchy>& hierarchy,
                    std::unique_ptr<WaveletTransform>& transform) {
  MW_ASSIGN_OR_RETURN(TransformSettings settings,
                      SetUpHierarchy(header, max_base_vertices, base, hierarchy));
  MW_ASSIGN_OR_RETURN(WaveletTransform t, WaveletTransform::Create(hierarchy, settings));
  transform = std::make_unique<WaveletTransform>(std::move(t));
  return Status::Ok();
}

}  // namespace meshwave
