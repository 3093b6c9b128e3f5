#include "meshwave/progression.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/protobuf_wire.h"
#include "core/quoted.h"
#include "meshwave/container.h"
#include "quant/deadzone_quantizer.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "stream/base_refinement.h"
#include "stream/stream_format.h"

namespace meshwave {
Result<Progression> ParseProgression(const std::string& name) {
  if (name == "quality") return Progression::kQuality;
  if (name == "resolution") return Progression::kResolution;
  if (name == "rd") return Progression::kRd;
  // The name may come from a client: quoted bounded and printable.
  return InvalidArgument("unknown order " + Quoted(name) + " (quality, resolution, rd)");
}

const char* ProgressionName(Progression p) {
  switch (p) {
    case Progression::kQuality: return "quality";
    case Progression::kResolution: return "resolution";
    case Progression::kRd: return "rd";
  }
  return "?";
}

Status ValidateStreamHeader(const StreamHeader& h) {
  MW_RETURN_IF_ERROR(ValidateVersionAndLevels(h));
  const uint32_t levels = h.transform.levels;
  MW_RETURN_IF_ERROR(ReadTransformSettings(h.transform).status());
  if (h.coder != StreamCoder::k3xC && h.coder != StreamCoder::kSim) {
    return ParseError("header: unknown coder " + std::to_string(static_cast<int32_t>(h.coder)));
  }
  if (h.octree_leaf_size == 0 || h.octree_leaf_size > (1u << 20)) {
    return ParseError("header: octree leaf size out of range");
  }
  MW_RETURN_IF_ERROR(ValidateQuantizers(h));
  if (h.base.refinement_planes > kMaxBaseRefinementPlanes) {
    return ParseError("header: " + std::to_string(h.base.refinement_planes) +
                      " base refinement planes (at most " +
                      std::to_string(kMaxBaseRefinementPlanes) + ")");
  }
  const auto& index = h.packets;
  if (index.precinct_coefficients > (1u << 30)) {
    return ParseError("header: precinct size out of range");
  }
  if (!index.split_planes.empty()) {
    if (index.split_planes.size() != levels) {
      return ParseError("header: " + std::to_string(index.split_planes.size()) +
                        " split plane counts for " + std::to_string(levels) + " subbands");
    }
    for (uint32_t j = 0; j < levels; ++j) {
      int top = -1;
      for (int c = 0; c < 3; ++c) top = std::max(top, h.quantizer(static_cast<int>(j), c).top_bitplane);
      const uint32_t split = index.split_planes[j];
      if (split > static_cast<uint32_t>(top + 1) || (split > 0 && index.precinct_coefficients == 0)) {
        return ParseError("header: subband " + std::to_string(j) + " splits " +
                          std::to_string(split) + " bitplanes" +
                          (split > 0 && index.precinct_coefficients == 0
                               ? " without precincts"
                               : " of " + std::to_string(top + 1)));
      }
    }
  }
  MW_RETURN_IF_ERROR(ValidateChannels(h));
  MW_RETURN_IF_ERROR(ValidateTexture(h));
  MW_RETURN_IF_ERROR(ValidateOriginal(h));
  const PacketLayout map(h);
  // One chain per subband and the base refinement's, then one per subband
  // of each channel, then one per texture map.
  MW_RETURN_IF_ERROR(ValidateCompactIndex(h, map.count(), static_cast<int>(ChainCount(h))));
  const uint64_t refinement_bytes = BaseRefinementBytes(h.base.vertex_count);
  for (int id = 0; id < map.count(); ++id) {
    const uint32_t length = index.length[static_cast<size_t>(id)];
    if (length > (1u << 30)) {
      return ParseError("header: packet " + std::to_string(id) + " is too long");
    }
    if (map.IsBase(static_cast<uint32_t>(id)) && length != refinement_bytes) {
      return ParseError("header: base refinement packet " + std::to_string(id) + " has " +
                        std::to_string(length) + " bytes, not " +
                        std::to_string(refinement_bytes) + " (3 bits per base vertex)");
    }
  }
  return Status::Ok();
}

std::vector<uint32_t> PacketDependencies(const StreamHeader& h,
                                         uint32_t id) {
  const PacketLayout::Needs needs = PacketLayout(h).Dependencies(id, h.coder == StreamCoder::k3xC);
  return {needs.begin(), needs.end()};
}

int BaseQualityShift(const StreamHeader& h) {
  if (h.quantizers.empty()) return 0;
  const double ratio = h.base.step / h.quantizers[0].step;
  if (!(ratio > 0) || !std::isfinite(ratio)) return 0;
  return static_cast<int>(std::floor(std::log2(ratio) + 0.5));
}

namespace {

// The quality order's texture levels (FORMAT.md 7): each map's levels
// coarsest first, each level before the first packet of `order` from which
// on no packet is worth more per byte (`value`) than it.
// `queues`: per map, its levels kept, coarsest first.
std::vector<uint32_t> MergeTextureLevels(const std::vector<uint32_t>& order,
                                         const std::vector<std::vector<uint32_t>>& queues,
                                         const std::vector<double>& value) {
  size_t levels = 0;
  for (const auto& queue : queues) levels += queue.size();
  if (levels == 0) return order;
  // The best value from each position of `order` on.
  std::vector<double> rest(order.size() + 1, -std::numeric_limits<double>::infinity());
  for (size_t i = order.size(); i-- > 0;) rest[i] = std::max(rest[i + 1], value[order[i]]);
  std::vector<size_t> next(queues.size(), 0);
  std::vector<uint32_t> out;
  out.reserve(order.size() + levels);
  // The most valuable next level of any map worth at least `floor` (ties:
  // the lower map), or none.
  auto take = [&](double floor) {
    int best = -1;
    for (size_t q = 0; q < queues.size(); ++q) {
      if (next[q] == queues[q].size()) continue;
      const uint32_t id = queues[q][next[q]];
      // NaN from an untrusted header never wins; it goes at the end.
      if (!(value[id] >= floor)) continue;
      if (best < 0 || value[id] > value[queues[static_cast<size_t>(best)][next[static_cast<size_t>(best)]]]) {
        best = static_cast<int>(q);
      }
    }
    if (best < 0) return false;
    out.push_back(queues[static_cast<size_t>(best)][next[static_cast<size_t>(best)]++]);
    return true;
  };
  for (size_t i = 0; i < order.size(); ++i) {
    while (take(rest[i])) {
    }
    out.push_back(order[i]);
  }
  while (take(-std::numeric_limits<double>::infinity())) {
  }
  for (size_t q = 0; q < queues.size(); ++q) {  // NaN values: last, in order
    for (; next[q] < queues[q].size(); ++next[q]) out.push_back(queues[q][next[q]]);
  }
  return out;
}

}  // namespace

std::vector<uint32_t> PacketOrder(const StreamHeader& h,
                                  Progression progression, int max_level) {
  const PacketLayout map(h);
  const int levels = map.levels();
  const int used = (max_level < 0 || max_level > levels) ? levels : max_level;
  int top = -1;
  for (int j = 0; j < used; ++j) top = std::max(top, map.Top(j));
  std::vector<uint32_t> order;
  // The channels' packets of bitplane n, subband by subband.
  auto channel_plane = [&](int n) {
    for (int k = 0; k < map.channels(); ++k) {
      for (int j = 0; j < used; ++j) {
        if (int id = map.ChannelId(k, j, n); id >= 0) order.push_back(static_cast<uint32_t>(id));
      }
    }
  };
  int channel_top = -1;
  for (int k = 0; k < map.channels(); ++k) {
    for (int j = 0; j < used; ++j) channel_top = std::max(channel_top, map.ChannelTop(k, j));
  }
  // The base refinement belongs to level 0, which every order draws. The
  // resolution order sends it first, as the whole base travelled in the
  // header before version 5; the quality order sends each plane with the
  // details' bitplane of the same step (BaseQualityShift); the rd order
  // weighs it as any other chain.
  const int base_planes = map.base_planes();
  auto base_plane = [&](int b) { order.push_back(static_cast<uint32_t>(map.BaseId(b))); };
  // Texture levels (FORMAT.md 7): level k of a map of L matches the mesh of
  // level J - (L-1-k) (both double their resolution a level), and is sent
  // only where that level is.
  auto texture_level_of = [&](uint32_t id) {
    const int m = map.TextureMap(id);
    return std::max(0, levels - (map.TextureLevels(m) - 1 - map.Bitplane(id)));
  };
  std::vector<uint32_t> textures;  // map by map, coarsest first
  std::vector<std::vector<uint32_t>> texture_queues;  // the same, per map
  for (int m = 0; m < map.texture_maps(); ++m) {
    texture_queues.emplace_back();
    for (int k = 0; k < map.TextureLevels(m); ++k) {
      const auto id = static_cast<uint32_t>(map.TextureId(m, k));
      if (texture_level_of(id) > used) continue;
      textures.push_back(id);
      texture_queues.back().push_back(id);
    }
  }
  // Every packet's reduction per byte, normalised as the rd order compares
  // them (FORMAT.md 7): the geometry's squared errors over diagonal², a
  // channel's and the texture's (peak 1) times their weights; all times
  // diagonal², so that the geometry's values are its reductions as they
  // are. Computed only for streams with textures or for the rd order.
  std::vector<double> value;
  if (!textures.empty() || progression == Progression::kRd) {
    const DistortionEstimates estimates = ReadDistortionIndex(h, PacketChains(h));
    const double diagonal = HeaderDiagonal(h);
    const double texture_scale =
        h.texture ? static_cast<double>(h.texture->rd_weight) * diagonal * diagonal : 0;
    value.assign(static_cast<size_t>(map.count()), 0);
    for (uint32_t id = 0; id < value.size() && id < estimates.reduction.size(); ++id) {
      double reduction = estimates.reduction[id];
      if (const int k = map.Channel(id); k >= 0) {
        reduction *= static_cast<double>(h.channels[static_cast<size_t>(k)].rd_weight) *
                     diagonal * diagonal;
      } else if (map.IsTexture(id)) {
        reduction *= texture_scale;
      }
      value[id] = reduction / (h.packets.length[id] + 4.0);
    }
  }
  switch (progression) {
    case Progression::kQuality: {
      const int shift = BaseQualityShift(h);
      // Planes coarser than every detail bitplane first.
      int b = base_planes - 1;
      for (; b >= 0 && b + shift > top; --b) base_plane(b);
      // A channel's bitplanes above the geometry's come first too; each
      // other channel bitplane follows the geometry's of the same number.
      for (int n = channel_top; n > top; --n) channel_plane(n);
      for (int n = top; n >= 0; --n) {
        for (; b >= 0 && b + shift == n; --b) base_plane(b);
        for (int j = 0; j < used; ++j) {
          if (int id = map.Id(j, n); id >= 0) order.push_back(static_cast<uint32_t>(id));
        }
        channel_plane(n);
      }
      for (; b >= 0; --b) base_plane(b);  // finer than every detail bitplane
      order = MergeTextureLevels(order, texture_queues, value);
      break;
    }
    case Progression::kResolution: {
      // The texture levels of mesh level n: after the packets that make it.
      auto texture_levels = [&](int n) {
        for (uint32_t id : textures) {
          if (texture_level_of(id) == n) order.push_back(id);
        }
      };
      for (int b = base_planes - 1; b >= 0; --b) base_plane(b);
      texture_levels(0);
      for (int j = 0; j < used; ++j) {
        for (int b = map.Top(j); b >= 0; --b) order.push_back(static_cast<uint32_t>(map.Id(j, b)));
        for (int k = 0; k < map.channels(); ++k) {
          for (int b = map.ChannelTop(k, j); b >= 0; --b) {
            order.push_back(static_cast<uint32_t>(map.ChannelId(k, j, b)));
          }
        }
        texture_levels(j + 1);
      }
      break;
    }
    case Progression::kRd: {
      // Greedy: among the packets whose dependencies are sent, the one with
      // the largest distortion reduction per byte (ties: lower id).
      std::vector<uint32_t> candidates;
      for (int j = 0; j < used; ++j) {
        for (int b = map.Top(j); b >= 0; --b) candidates.push_back(static_cast<uint32_t>(map.Id(j, b)));
      }
      for (int b = map.base_planes() - 1; b >= 0; --b) {
        candidates.push_back(static_cast<uint32_t>(map.BaseId(b)));
      }
      for (int k = 0; k < map.channels(); ++k) {
        for (int j = 0; j < used; ++j) {
          for (int b = map.ChannelTop(k, j); b >= 0; --b) {
            candidates.push_back(static_cast<uint32_t>(map.ChannelId(k, j, b)));
          }
        }
      }
      candidates.insert(candidates.end(), textures.begin(), textures.end());
      std::vector<char> sent(h.packets.length.size(), 0);
      while (order.size() < candidates.size()) {
        int best = -1;
        double best_value = -1;
        for (uint32_t id : candidates) {
          if (sent[id]) continue;
          bool ready = true;
          for (uint32_t d : map.Dependencies(id, h.coder == StreamCoder::k3xC)) {
            ready = ready && sent[d];
          }
          // A map's levels, each a whole image, go coarsest first: each
          // level's reduction is counted from the one before.
          if (map.IsTexture(id) && map.Bitplane(id) > 0) ready = ready && sent[id - 1];
          if (!ready) continue;
          const double v = value[id];
          // The first ready packet is taken whatever its value: an untrusted
          // header may give reductions below -1 or NaN (fuzz_replay_container_fuzz).
          if (best < 0 || v > best_value || (v == best_value && static_cast<int>(id) < best)) {
            best = static_cast<int>(id);
            best_value = v;
          }
        }
        if (best < 0) break;  // nothing ready: cannot happen on a validated header
        sent[best] = 1;
        order.push_back(static_cast<uint32_t>(best));
      }
      break;
    }
  }
  AppendOriginalLayer(map, used, order);
  return order;
}

uint64_t PacketLength(const StreamHeader& h, uint32_t id) {
  return h.packets.length[id];
}

Selection SelectPayloads(const StreamHeader& h,
                         const std::vector<uint32_t>& order, uint64_t budget,
                         size_t cursor) {
  Selection s;
  s.next_cursor = std::min(cursor, order.size());
  while (s.next_cursor < order.size()) {
    const uint32_t id = order[s.next_cursor];
    const uint64_t next = s.bytes + h.packets.length[id];
    if (next > budget) break;
    s.bytes = next;
    s.ids.push_back(id);
    ++s.next_cursor;
  }
  return s;
}

Selection SelectPackets(const StreamHeader& h,
                        const std::vector<uint32_t>& order, uint64_t budget,
                        size_t cursor) {
  if (cursor > 0) return SelectPayloads(h, order, budget, cursor);
  Selection s;
  // The container's size is the header's plus, per packet, its payload and
  // its id in `present`: sizes are added, not recomputed (ContainerSize
  // walks the whole header; calling it per packet made fitting a budget
  // quadratic in the packet count).
  const uint64_t empty = ContainerSize(h, {});
  if (empty > budget) return s;  // not even the header fits
  uint64_t payload = 0, id_bytes = 0;
  s.bytes = empty;
  while (s.next_cursor < order.size()) {
    const uint32_t id = order[s.next_cursor];
    const uint64_t length = h.packets.length[id];
    const uint64_t ids = id_bytes + VarintSize(id);
    const uint64_t next = empty + payload + length + PresentFieldSize(ids);
    if (next > budget) break;
    id_bytes = ids;
    payload += length;
    s.bytes = next;
    s.ids.push_back(id);
    ++s.next_cursor;
  }
  return s;
}

}  // namespace meshwave
