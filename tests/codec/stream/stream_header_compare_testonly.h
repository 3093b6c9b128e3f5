// The field-by-field comparison of ReadStreamHeader's result with
// protobuf's parse of the same bytes (stream_header_test, and the
// stream_header_fuzz differential target). Doubles and floats compare bit
// for bit (a NaN equals the same NaN); `sawt` compares presence too.
#ifndef MESHWAVE_TESTS_STREAM_HEADER_COMPARE_TESTONLY_H_
#define MESHWAVE_TESTS_STREAM_HEADER_COMPARE_TESTONLY_H_

#include <cstring>
#include <string>

#include "meshwave/stream_header.h"
#include "stream.pb.h"

namespace meshwave::testing {

namespace header_compare_internal {

template <class T>
bool SameBits(T a, T b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

template <class T, class R>
bool SameFloats(const std::vector<T>& a, const R& b) {
  if (a.size() != static_cast<size_t>(b.size())) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (!SameBits(a[i], b.Get(static_cast<int>(i)))) return false;
  }
  return true;
}

template <class T, class R>
bool SameInts(const std::vector<T>& a, const R& b) {
  return a.size() == static_cast<size_t>(b.size()) && std::equal(a.begin(), a.end(), b.begin());
}

}  // namespace header_compare_internal

// "" when every field agrees, else the name of the first that does not.
inline std::string HeaderDifference(const StreamHeader& r, const proto::StreamHeader& p) {
  using namespace header_compare_internal;
  if (r.format_version != p.format_version()) return "format_version";
  if (r.name != p.name()) return "name";
  if (r.vertices != p.vertices()) return "vertices";
  if (r.faces != p.faces()) return "faces";
  if (!SameFloats(r.bbox_min, p.bbox_min())) return "bbox_min";
  if (!SameFloats(r.bbox_max, p.bbox_max())) return "bbox_max";
  const auto& t = p.transform();
  if (static_cast<int32_t>(r.transform.predictor) != t.predictor()) return "transform.predictor";
  if (static_cast<int32_t>(r.transform.update) != t.update()) return "transform.update";
  if (r.transform.local_frames != t.local_frames()) return "transform.local_frames";
  if (r.transform.levels != t.levels()) return "transform.levels";
  if (r.transform.sawt.has_value() != t.has_sawt()) return "transform.sawt presence";
  if (r.transform.sawt) {
    const auto& s = t.sawt();
    if (r.transform.sawt->alpha != s.alpha()) return "transform.sawt.alpha";
    if (r.transform.sawt->region_count != s.region_count()) return "transform.sawt.region_count";
    if (r.transform.sawt->coded != s.coded()) return "transform.sawt.coded";
    if (r.transform.sawt->crc32c != s.crc32c()) return "transform.sawt.crc32c";
  }
  if (static_cast<int32_t>(r.coder) != p.coder()) return "coder";
  if (r.octree_leaf_size != p.octree_leaf_size()) return "octree_leaf_size";
  const auto& b = p.base();
  if (r.base.vertex_count != b.vertex_count()) return "base.vertex_count";
  if (r.base.face_count != b.face_count()) return "base.face_count";
  if (!SameFloats(r.base.origin, b.origin())) return "base.origin";
  if (!SameBits(r.base.step, b.step())) return "base.step";
  if (r.base.coded != b.coded()) return "base.coded";
  if (r.quantizers.size() != static_cast<size_t>(p.quantizers_size())) return "quantizers size";
  for (size_t i = 0; i < r.quantizers.size(); ++i) {
    const auto& q = p.quantizers(static_cast<int>(i));
    if (!SameBits(r.quantizers[i].step, q.step())) return "quantizers.step";
    if (r.quantizers[i].deadzone != q.deadzone()) return "quantizers.deadzone";
    if (r.quantizers[i].top_bitplane != q.top_bitplane()) return "quantizers.top_bitplane";
  }
  const auto& x = p.packets();
  if (!SameInts(r.packets.length, x.length())) return "packets.length";
  if (r.packets.check != x.check()) return "packets.check";
  if (!SameFloats(r.packets.chain_distortion, x.chain_distortion())) {
    return "packets.chain_distortion";
  }
  if (r.packets.distortion_step != x.distortion_step()) return "packets.distortion_step";
  if (r.packets.precinct_coefficients != x.precinct_coefficients()) {
    return "packets.precinct_coefficients";
  }
  if (!SameInts(r.packets.split_planes, x.split_planes())) return "packets.split_planes";
  if (!SameBits(r.base_distortion, p.base_distortion())) return "base_distortion";
  if (!SameInts(r.present, p.present())) return "present";
  if (r.channels.size() != static_cast<size_t>(p.channels_size())) return "channels size";
  for (size_t k = 0; k < r.channels.size(); ++k) {
    const auto& c = p.channels(static_cast<int>(k));
    const StreamHeader::Channel& rc = r.channels[k];
    if (static_cast<int32_t>(rc.kind) != c.kind()) return "channels.kind";
    if (!SameBits(rc.base_step, c.base_step())) return "channels.base_step";
    if (rc.base != c.base()) return "channels.base";
    if (!SameBits(rc.rd_weight, c.rd_weight())) return "channels.rd_weight";
    if (rc.quantizers.size() != static_cast<size_t>(c.quantizers_size())) {
      return "channels.quantizers size";
    }
    for (size_t i = 0; i < rc.quantizers.size(); ++i) {
      const auto& q = c.quantizers(static_cast<int>(i));
      if (!SameBits(rc.quantizers[i].step, q.step())) return "channels.quantizers.step";
      if (rc.quantizers[i].deadzone != q.deadzone()) return "channels.quantizers.deadzone";
      if (rc.quantizers[i].top_bitplane != q.top_bitplane()) {
        return "channels.quantizers.top_bitplane";
      }
    }
  }
  if (r.texture.has_value() != p.has_texture()) return "texture presence";
  if (r.texture) {
    const auto& px = p.texture();
    const StreamHeader::Texture& rt = *r.texture;
    if (rt.cell != px.cell() || rt.gutter != px.gutter() || rt.columns != px.columns()) {
      return "texture.atlas";
    }
    if (!SameInts(rt.face_triangles, px.face_triangles())) return "texture.face_triangles";
    if (!SameBits(rt.metallic_factor, px.metallic_factor()) ||
        !SameBits(rt.roughness_factor, px.roughness_factor()) ||
        !SameFloats(rt.emissive_factor, px.emissive_factor()) ||
        !SameBits(rt.normal_scale, px.normal_scale()) ||
        !SameBits(rt.occlusion_strength, px.occlusion_strength()) ||
        rt.alpha_blend != px.alpha_blend() || rt.double_sided != px.double_sided()) {
      return "texture.material";
    }
    if (!SameBits(rt.rd_weight, px.rd_weight())) return "texture.rd_weight";
    if (rt.maps.size() != static_cast<size_t>(px.maps_size())) return "texture.maps size";
    for (size_t m = 0; m < rt.maps.size(); ++m) {
      const auto& map = px.maps(static_cast<int>(m));
      if (rt.maps[m].role != static_cast<int32_t>(map.role())) return "texture.maps.role";
      if (rt.maps[m].mime_type != map.mime_type()) return "texture.maps.mime_type";
      if (rt.maps[m].levels.size() != static_cast<size_t>(map.levels_size())) {
        return "texture.maps.levels size";
      }
      for (size_t k = 0; k < rt.maps[m].levels.size(); ++k) {
        const auto& l = map.levels(static_cast<int>(k));
        const StreamHeader::Texture::Level& rl = rt.maps[m].levels[k];
        if (rl.packet != l.packet() || rl.width != l.width() || rl.height != l.height()) {
          return "texture.maps.levels";
        }
      }
    }
  }
  return "";
}

// protobuf's serialization of `p` without its `present` list.
inline std::string ProtoBytesWithoutPresent(proto::StreamHeader p) {
  p.clear_present();
  return p.SerializeAsString();
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_STREAM_HEADER_COMPARE_TESTONLY_H_
