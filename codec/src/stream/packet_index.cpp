#include "stream/packet_index.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/crc.h"
#include "meshwave/stream_limits.h"
#include "stream/stream_format.h"

namespace meshwave {

uint16_t PacketCheck(std::string_view payload) {
  return Crc16CcittFalse(payload);
}

bool PacketCheckMatches(const StreamHeader::PacketIndex& index, uint32_t id,
                        std::string_view payload) {
  const std::string& check = index.check;
  if (check.size() < 2 * (static_cast<size_t>(id) + 1)) return false;
  const auto hi = static_cast<uint8_t>(check[2 * id]);
  const auto lo = static_cast<uint8_t>(check[2 * id + 1]);
  return PacketCheck(payload) == static_cast<uint16_t>(hi << 8 | lo);
}

PacketLayout::PacketLayout(const StreamHeader& h) {
  const int levels = static_cast<int>(
      std::min<uint64_t>(h.transform.levels, h.quantizers.size() / 3));
  for (int j = 0; j < levels; ++j) {
    int top = -1;
    for (int c = 0; c < 3; ++c) top = std::max(top, h.quantizer(j, c).top_bitplane);
    top = std::max(top, -1);
    first_.push_back(count_);
    top_.push_back(top);
    for (int b = top; b >= 0; --b) subband_.push_back(j);
    count_ += top + 1;
  }
  detail_count_ = count_;
  split_planes_ = h.packets.split_planes;
  // Clamped for headers not validated yet (ValidateStreamHeader refuses more).
  base_planes_ = static_cast<int>(
      std::min<uint32_t>(h.base.refinement_planes, kMaxBaseRefinementPlanes));
  subband_.insert(subband_.end(), static_cast<size_t>(base_planes_), -1);
  count_ += base_planes_;
  channel_.assign(static_cast<size_t>(count_), -1);
  const size_t channels = std::min<size_t>(h.channels.size(), kMaxChannels);
  for (size_t k = 0; k < channels; ++k) {
    const StreamHeader::Channel& channel = h.channels[k];
    std::vector<int>& first = channel_first_.emplace_back();
    std::vector<int>& tops = channel_top_.emplace_back();
    for (int j = 0; j < levels; ++j) {
      int top = -1;
      if (channel.quantizers.size() >= 3 * (static_cast<size_t>(j) + 1)) {
        for (int c = 0; c < 3; ++c) top = std::max(top, channel.quantizer(j, c).top_bitplane);
      }
      top = std::max(top, -1);
      first.push_back(count_);
      tops.push_back(top);
      for (int b = top; b >= 0; --b) {
        subband_.push_back(j);
        channel_.push_back(static_cast<int>(k));
      }
      count_ += top + 1;
    }
  }
  channel_.resize(static_cast<size_t>(count_), -1);
  texture_.assign(static_cast<size_t>(count_), -1);
  if (h.texture) {
    // Clamped for headers not validated yet (ValidateTexture refuses more).
    const size_t maps = std::min<size_t>(h.texture->maps.size(), kMaxTextureMaps);
    for (size_t m = 0; m < maps; ++m) {
      const auto map_levels = static_cast<int>(
          std::min<size_t>(h.texture->maps[m].levels.size(), kMaxTextureLevels));
      texture_first_.push_back(count_);
      texture_levels_.push_back(map_levels);
      subband_.insert(subband_.end(), static_cast<size_t>(map_levels), -1);
      channel_.insert(channel_.end(), static_cast<size_t>(map_levels), -1);
      texture_.insert(texture_.end(), static_cast<size_t>(map_levels), static_cast<int>(m));
      count_ += map_levels;
    }
  }
  original_first_ = count_;
  if (h.original) {
    // Clamped for headers not validated yet (ValidateOriginal refuses more).
    const int parts = 2 + static_cast<int>(std::min<uint32_t>(h.original->refinement_planes,
                                                              kMaxOriginalRefinementPlanes));
    subband_.insert(subband_.end(), static_cast<size_t>(parts), -1);
    channel_.insert(channel_.end(), static_cast<size_t>(parts), -1);
    texture_.insert(texture_.end(), static_cast<size_t>(parts), -1);
    count_ += parts;
  }
}

int PacketLayout::TextureId(int map, int level) const {
  if (map < 0 || map >= texture_maps() || level < 0 || level >= TextureLevels(map)) return -1;
  return texture_first_[static_cast<size_t>(map)] + level;
}

int PacketLayout::BaseId(int plane) const {
  if (plane < 0 || plane >= base_planes_) return -1;
  return detail_count_ + (base_planes_ - 1 - plane);
}

int PacketLayout::ChannelId(int k, int j, int b) const {
  if (k < 0 || k >= channels() || j < 0 || j >= levels()) return -1;
  const int top = channel_top_[static_cast<size_t>(k)][static_cast<size_t>(j)];
  if (b < 0 || b > top) return -1;
  return channel_first_[static_cast<size_t>(k)][static_cast<size_t>(j)] + (top - b);
}

int PacketLayout::Id(int j, int b) const {
  if (j < 0 || j >= levels() || b < 0 || b > top_[static_cast<size_t>(j)]) return -1;
  return first_[static_cast<size_t>(j)] + (top_[static_cast<size_t>(j)] - b);
}

PacketLayout::Needs PacketLayout::Dependencies(uint32_t id, bool parent_contexts) const {
  Needs needs;
  if (id >= static_cast<uint32_t>(count()) || IsTexture(id)) return needs;
  if (const int part = OriginalPart(id); part >= 0) {
    // Each part needs the one before: positions need the traversal.
    if (part > 0) needs.ids[needs.count++] = id - 1;
    return needs;
  }
  if (IsBase(id)) {
    if (int up = BaseId(Bitplane(id) + 1); up >= 0) {
      needs.ids[needs.count++] = static_cast<uint32_t>(up);
    }
    return needs;
  }
  const int j = Subband(id);
  const int b = Bitplane(id);
  const int k = Channel(id);
  auto id_of = [&](int jj, int bb) { return k < 0 ? Id(jj, bb) : ChannelId(k, jj, bb); };
  if (int up = id_of(j, b + 1); up >= 0) needs.ids[needs.count++] = static_cast<uint32_t>(up);
  if (parent_contexts) {
    if (int parent = id_of(j - 1, b); parent >= 0) {
      needs.ids[needs.count++] = static_cast<uint32_t>(parent);
    }
  }
  return needs;
}

int PacketLayout::Bitplane(uint32_t id) const {
  if (IsBase(id)) return base_planes_ - 1 - (static_cast<int>(id) - detail_count_);
  if (const int part = OriginalPart(id); part >= 0) return part;
  if (const int m = TextureMap(id); m >= 0) {
    return static_cast<int>(id) - texture_first_[static_cast<size_t>(m)];
  }
  const auto j = static_cast<size_t>(subband_[id]);
  if (const int k = Channel(id); k >= 0) {
    const auto kk = static_cast<size_t>(k);
    return channel_top_[kk][j] - (static_cast<int>(id) - channel_first_[kk][j]);
  }
  return top_[j] - (static_cast<int>(id) - first_[j]);
}

std::vector<uint32_t> PacketChains(const StreamHeader& header) {
  const int count = static_cast<int>(header.packets.length.size());
  std::vector<uint32_t> chain(static_cast<size_t>(count), 0);
  const PacketLayout layout(header);
  const int levels = layout.levels();
  for (int id = 0; id < count && id < layout.count(); ++id) {
    const auto u = static_cast<uint32_t>(id);
    int c = layout.IsBase(u) ? levels : layout.Subband(u);
    if (const int k = layout.Channel(u); k >= 0) c = levels + 1 + k * levels + layout.Subband(u);
    if (const int m = layout.TextureMap(u); m >= 0) {
      c = levels + 1 + layout.channels() * levels + m;
    }
    if (layout.IsOriginal(u)) c = levels + 1 + layout.channels() * levels + layout.texture_maps();
    chain[static_cast<size_t>(id)] = static_cast<uint32_t>(c);
  }
  return chain;
}

size_t ChainCount(const StreamHeader& header) {
  const PacketLayout layout(header);
  const auto levels = static_cast<size_t>(layout.levels());
  return levels + 1 + static_cast<size_t>(layout.channels()) * levels +
         static_cast<size_t>(layout.texture_maps()) + (header.original ? 1 : 0);
}

double HeaderDiagonal(const StreamHeader& header) {
  double diagonal = 0;
  for (size_t a = 0; a < 3 && a < header.bbox_min.size() && a < header.bbox_max.size(); ++a) {
    const double d = header.bbox_max[a] - header.bbox_min[a];
    diagonal += d * d;
  }
  return std::sqrt(diagonal);
}

double EstimatedPsnrFromDistortion(const StreamHeader& header, double diagonal,
                                   double distortion) {
  const double vertices = static_cast<double>(std::max<uint64_t>(header.vertices, 1));
  const double mse = std::max(distortion, 0.0) / vertices;
  if (mse <= 0) return std::numeric_limits<double>::infinity();
  return 20 * std::log10(diagonal / std::sqrt(mse));
}

double DistortionEstimates::Estimate(const std::vector<double>& current) const {
  double d = base;
  for (size_t c = 0; c < current.size() && c < geometry_chains; ++c) d += current[c];
  return d;
}

DistortionEstimates ReadDistortionIndex(const StreamHeader& header,
                                        std::span<const uint32_t> chain_of) {
  const StreamHeader::PacketIndex& index = header.packets;
  DistortionEstimates out;
  out.base = header.base_distortion;
  for (float e : index.chain_distortion) out.chain_start.push_back(e);
  // Chains of other signals than the geometry (channels, texture maps, the
  // original layer): after the geometry's, not summed into its estimate.
  const size_t other_chains =
      std::min<size_t>(header.channels.size(), kMaxChannels) * header.transform.levels +
      (header.texture ? std::min<size_t>(header.texture->maps.size(), kMaxTextureMaps) : 0) +
      (header.original ? 1 : 0);
  out.geometry_chains =
      out.chain_start.size() - std::min(out.chain_start.size(), other_chains);
  if (header.original && !out.chain_start.empty()) {
    out.original_chain = static_cast<int>(out.chain_start.size()) - 1;
  }
  std::vector<double> current = out.chain_start;
  const std::string& steps = index.distortion_step;
  out.chain.assign(chain_of.begin(), chain_of.end());
  out.after.assign(chain_of.size(), 0.0);
  out.reduction.assign(chain_of.size(), 0.0);
  for (size_t i = 0; i < chain_of.size() && i < steps.size(); ++i) {
    const uint32_t c = chain_of[i];
    if (c >= current.size()) continue;
    const int d = static_cast<uint8_t>(steps[i]);
    const double next = d == 255 ? 0.0 : current[c] * std::exp2(-d / kDistortionCodesPerOctave);
    out.reduction[i] = current[c] - next;
    out.after[i] = next;
    current[c] = next;
  }
  return out;
}

Status ValidateCompactIndex(const StreamHeader& header, int packet_count,
                            int chains) {
  const StreamHeader::PacketIndex& index = header.packets;
  if (index.length.size() != static_cast<size_t>(packet_count)) {
    return ParseError("header: " + std::to_string(index.length.size()) +
                      " packet lengths, " + std::to_string(packet_count) +
                      " packets expected from the quantizers");
  }
  if (index.check.size() != 2 * static_cast<size_t>(packet_count) ||
      index.distortion_step.size() != static_cast<size_t>(packet_count)) {
    return ParseError("header: packet index arrays differ in length");
  }
  if (index.chain_distortion.size() != static_cast<size_t>(chains)) {
    return ParseError("header: " + std::to_string(index.chain_distortion.size()) +
                      " chain distortions, " + std::to_string(chains) + " expected");
  }
  for (float e : index.chain_distortion) {
    if (!(e >= 0) || !std::isfinite(e)) return ParseError("header: a chain distortion is out of range");
  }
  if (!(header.base_distortion >= 0) || !std::isfinite(header.base_distortion)) {
    return ParseError("header: base distortion out of range");
  }
  return Status::Ok();
}

}  // namespace meshwave
