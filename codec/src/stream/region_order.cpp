#include "meshwave/region_order.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <span>
#include <utility>
#include <variant>

#include "meshwave/packet_parts.h"
#include "meshwave/semiregular.h"
#include "semiregular/base_face_of.h"
#include "stream/decoder_setup.h"
#include "stream/packet_index.h"
#include "stream/precinct_partition.h"
#include "stream/screen_error_selection.h"
#include "stream/stream_format.h"

namespace meshwave {

Result<StreamPrecincts> StreamPrecincts::Create(const StreamHeader& header) {
  DecodedBase base;
  std::shared_ptr<const SemiRegularHierarchy> hierarchy;
  MW_RETURN_IF_ERROR(
      SetUpHierarchy(header, kMaxBaseVertices, base, hierarchy).status());
  const SemiRegularHierarchy& h = *hierarchy;
  const PrecinctPartition partition = PartitionIntoPrecincts(
      h, base.grid, header.packets.precinct_coefficients);
  const auto& faces = h.faces(0);
  StreamPrecincts out;
  for (int j = 0; j < h.levels(); ++j) {
    Subband s;
    const uint32_t count = partition.count(j);
    std::vector<double> held(faces.size(), 0);
    AddCoefficientsPerBaseFace(h, j, held);
    const double total =
        std::max<double>(1, static_cast<double>(h.subband_size(j)));
    for (uint32_t p = 0; p < count; ++p) {
      s.parent.push_back(j == 0 ? 0 : partition.Parent(j, p));
      Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
      Vec3 hi = -lo;
      double coefficients = 0;
      const auto& bounds = partition.bounds[static_cast<size_t>(j)];
      for (uint32_t i = bounds[p]; i < bounds[p + 1]; ++i) {
        const uint32_t f = partition.face_order[i];
        coefficients += held[f];
        for (uint32_t v : faces[f]) {
          lo = lo.cwiseMin(base.positions[v]);
          hi = hi.cwiseMax(base.positions[v]);
        }
      }
      const bool empty = bounds[p] == bounds[p + 1];
      s.centre.push_back(empty ? Vec3::Zero() : Vec3(0.5 * (lo + hi)));
      s.radius.push_back(empty ? 0.0 : 0.5 * (hi - lo).norm());
      s.share.push_back(coefficients / total);
    }
    out.subbands_.push_back(std::move(s));
  }
  return out;
}

PrecinctParents StreamPrecincts::parents() const {
  PrecinctParents out;
  for (const Subband& s : subbands_) out.push_back(s.parent);
  return out;
}

Result<std::vector<std::string_view>> PacketParts(const HeldUnits& units,
                                                  uint32_t id,
                                                  std::string_view payload) {
  const uint32_t count = units.PartCount(id);
  if (count == 0)
    return ParseError("packet " + std::to_string(id) + " is not split");
  return SplitPacketParts(payload, count);
}

Result<std::vector<uint32_t>> PartLengths(const HeldUnits& units, uint32_t id,
                                          std::string_view payload) {
  const uint32_t count = units.PartCount(id);
  std::vector<uint32_t> out;
  if (count == 0) return out;
  MW_ASSIGN_OR_RETURN(std::vector<std::string_view> parts,
                      SplitPacketParts(payload, count));
  for (std::string_view part : parts)
    out.push_back(static_cast<uint32_t>(part.size()));
  return out;
}

std::vector<StreamUnit> RegionOrder(
    const StreamHeader& header, const StreamPrecincts& precincts,
    std::span<const std::vector<uint32_t>> part_lengths, const Region& region,
    const HeldUnits& held, int max_level, const StreamScreenErrors* measured) {
  const PacketLayout layout(header);
  const uint32_t n = static_cast<uint32_t>(layout.count());
  const DistortionEstimates estimates =
      ReadDistortionIndex(header, PacketChains(header));
  const int levels = std::min(layout.levels(), precincts.levels());
  const int used = (max_level < 0 || max_level > levels) ? levels : max_level;
  // Weights of every precinct, and per subband their share-weighted sum;
  // whether a precinct is in the region: it meets the sphere, or the view
  // sees it. A precinct's parent precinct holds its faces, so it is in the
  // region too: what a unit in the region needs is in it.
  const bool sphere = std::holds_alternative<SphereRegion>(region.shape);
  auto inside = [&](double w) { return sphere ? w >= 1 : w > 0; };
  std::vector<std::vector<double>> weight(static_cast<size_t>(levels));
  std::vector<double> subband_weight(static_cast<size_t>(levels), 0);
  std::vector<char> subband_inside(static_cast<size_t>(levels), 0);
  for (int j = 0; j < levels; ++j) {
    for (uint32_t p = 0; p < precincts.count(j); ++p) {
      const double w =
          RegionWeight(region, precincts.centre(j, p), precincts.radius(j, p));
      weight[static_cast<size_t>(j)].push_back(w);
      subband_weight[static_cast<size_t>(j)] += precincts.share(j, p) * w;
      subband_inside[static_cast<size_t>(j)] |= inside(w) ? 1 : 0;
    }
  }
  // The candidate units: index first_unit[id] + part.
  std::vector<StreamUnit> units;
  std::vector<uint32_t> first_unit(n, 0);
  std::vector<char> wanted(n, 0);
  for (uint32_t id = 0; id < n; ++id) {
    first_unit[id] = static_cast<uint32_t>(units.size());
    const int j = layout.Subband(id);
    // The original layer is global and last (FORMAT.md 7): appended below.
    if (layout.IsOriginal(id)) continue;
    if (layout.IsTexture(id)) {
      // Texture levels are global (one image for the whole surface): each
      // one where the uniform orders send it (its mesh level within
      // max_level), ranked with the region's units by its value.
      const int m = layout.TextureMap(id);
      const int level =
          layout.levels() - (layout.TextureLevels(m) - 1 - layout.Bitplane(id));
      if (std::max(level, 0) > used) continue;
      wanted[id] = 1;
      units.push_back({id, StreamUnit::kWholePacket});
      continue;
    }
    // Channels are not refined by region yet: their packets travel in the
    // uniform orders only.
    if (layout.IsChannel(id) || j >= used || (j >= 0 && j >= levels)) continue;
    wanted[id] = 1;
    const uint32_t parts = held.PartCount(id);
    if (parts == 0 || id >= part_lengths.size() ||
        part_lengths[id].size() != parts) {
      units.push_back({id, StreamUnit::kWholePacket});
    } else {
      for (uint32_t p = 0; p < parts; ++p) units.push_back({id, p});
    }
  }
  const size_t count = units.size();
  const ScreenErrorSelection screen =
      ScreenErrorSelection::Of(header, layout, precincts, part_lengths, held,
                            region, levels, measured);
  // By the screen-space error, when one is asked.
  std::vector<char> needed(count, 1);
  std::vector<double> gain(count, 0), cost(count, 0);
  std::vector<char> in_region(count, 0);  // before every other unit
  std::vector<uint32_t> pending(count, 0);
  // Dependencies as edges (d, k): unit k needs unit d; generated in
  // increasing k, so each unit's needs are one run of `edges`.
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  std::vector<uint32_t> needs_first(count + 1, 0);
  std::vector<uint64_t> packet_total(n, 0);  // a split packet's part bytes
  for (uint32_t id = 0; id < n && id < part_lengths.size(); ++id) {
    for (uint32_t l : part_lengths[id]) packet_total[id] += l;
  }
  for (uint32_t k = 0; k < count; ++k) {
    const StreamUnit& u = units[k];
    const uint32_t bytes =
        u.whole() ? header.packets.length[u.id] : part_lengths[u.id][u.part];
    double reduction = estimates.reduction[u.id];
    const int j = layout.Subband(u.id);
    const int b = layout.Bitplane(u.id);
    double w = 0;
    if (layout.IsTexture(u.id)) {
      // Normalised as PacketOrder's rd order weighs it (FORMAT.md 7).
      const double diagonal = HeaderDiagonal(header);
      w = static_cast<double>(header.texture->rd_weight) * diagonal * diagonal;
      in_region[k] = 1;
    } else if (j < 0) {
      w = levels > 0 ? subband_weight[0] : 1;
      in_region[k] = levels == 0 || subband_inside[0];
      if (screen.active) needed[k] = screen.BaseNeeded(u.id, b);
    } else if (u.whole()) {
      w = subband_weight[static_cast<size_t>(j)];
      in_region[k] = subband_inside[static_cast<size_t>(j)];
      if (screen.active) needed[k] = screen.PacketNeeded(u.id, j, b);
    } else {
      const uint64_t total = packet_total[u.id];
      reduction *= total > 0
                       ? static_cast<double>(bytes) / static_cast<double>(total)
                       : 0;
      w = weight[static_cast<size_t>(j)][u.part];
      in_region[k] = inside(w);
      if (screen.active) needed[k] = screen.PartNeeded(u.id, j, b, u.part);
    }
    // An untrusted header may give negative or NaN reductions: worth 0.
    // Each unit's record or message costs a few bytes more; a unit of no
    // bytes (a precinct with nothing at that bitplane) costs nothing.
    const double g = w * reduction;
    gain[k] = g > 0 ? g : 0;
    cost[k] = bytes == 0 ? 0 : bytes + 4.0;
    std::array<std::pair<int, int>, 2> needs{};  // (packet, its subband)
    int need_count = 0;
    if (layout.IsTexture(u.id)) {
      // A map's levels go coarsest first, as in the rd order.
      if (b > 0) needs[need_count++] = {static_cast<int>(u.id) - 1, -1};
    } else if (j < 0) {
      needs[need_count++] = {layout.BaseId(b + 1), -1};
    } else {
      needs[need_count++] = {layout.Id(j, b + 1), j};
      if (header.coder == StreamCoder::k3xC && j > 0)
        needs[need_count++] = {layout.Id(j - 1, b), j - 1};
    }
    auto need = [&](uint32_t d) {
      if (held.Has(units[d])) return;
      ++pending[k];
      edges.push_back({d, k});
    };
    for (int i = 0; i < need_count; ++i) {
      const auto [id, jj] = needs[static_cast<size_t>(i)];
      if (id < 0 || !wanted[static_cast<uint32_t>(id)]) continue;
      // The units of packet `id` that u needs: its precinct's part (or
      // the parent precinct's), else all of them.
      const auto q = static_cast<uint32_t>(id);
      const uint32_t first = first_unit[q];
      const uint32_t last =
          q + 1 < n ? first_unit[q + 1] : static_cast<uint32_t>(count);
      if (last - first <= 1 || u.whole()) {
        for (uint32_t d = first; d < last; ++d) need(d);
      } else {
        need(first + (jj == j ? u.part : precincts.parent(j, u.part)));
      }
    }
    needs_first[k + 1] = static_cast<uint32_t>(edges.size());
  }
  // Each unit's dependants, in increasing order (a counting sort of the
  // edges by d keeps their order of k).
  std::vector<uint32_t> dependants_first(count + 1, 0), dependants(edges.size());
  for (const auto& e : edges) ++dependants_first[e.first + 1];
  for (size_t k = 0; k < count; ++k) dependants_first[k + 1] += dependants_first[k];
  {
    std::vector<uint32_t> at(dependants_first.begin(), dependants_first.end() - 1);
    for (const auto& e : edges) dependants[at[e.first]++] = e.second;
  }
  auto dependants_of = [&](uint32_t k) {
    return std::span<const uint32_t>(dependants.data() + dependants_first[k],
                                     dependants.data() + dependants_first[k + 1]);
  };
  // What a needed unit needs is needed too (dependencies have lower
  // indices: one pass from the end). Whatever is not needed is not sent.
  for (uint32_t k = static_cast<uint32_t>(count); k-- > 0;) {
    if (needed[k]) {
      for (uint32_t e = needs_first[k]; e < needs_first[k + 1]; ++e) needed[edges[e].first] = 1;
    }
  }
  // A unit's value: the best gain per byte of a chain of units starting
  // with it (itself, then a unit that needs it, and so on): a unit of
  // little worth that opens the way to much (an empty part before a rich
  // one, a part whose finer parts matter) is not left behind. Dependants
  // have higher indices (they need lower packet ids): one pass from the
  // end.
  auto ratio = [](double g, double c) {
    return c > 0 ? g / c
                 : (g > 0 || c == 0 ? std::numeric_limits<double>::infinity()
                                    : 0.0);
  };
  std::vector<double> chain_gain(gain), chain_cost(cost), value(count, 0);
  for (uint32_t k = static_cast<uint32_t>(count); k-- > 0;) {
    for (uint32_t d : dependants_of(k)) {
      const double g = gain[k] + chain_gain[d], c = cost[k] + chain_cost[d];
      if (ratio(g, c) > ratio(chain_gain[k], chain_cost[k])) {
        chain_gain[k] = g;
        chain_cost[k] = c;
      }
    }
    value[k] = ratio(chain_gain[k], chain_cost[k]);
  }
  // Kahn's algorithm: the ready units in the region first, among them (and
  // then among the others) the most valuable (ties: the lower index, so
  // the order is deterministic).
  auto less = [&](uint32_t a, uint32_t b) {
    if (in_region[a] != in_region[b]) return in_region[a] < in_region[b];
    return value[a] < value[b] || (value[a] == value[b] && a > b);
  };
  std::priority_queue<uint32_t, std::vector<uint32_t>, decltype(less)> ready(
      less);
  for (uint32_t k = 0; k < count; ++k) {
    if (needed[k] && !held.Has(units[k]) && pending[k] == 0) ready.push(k);
  }
  std::vector<StreamUnit> order;
  order.reserve(count);
  while (!ready.empty()) {
    const uint32_t k = ready.top();
    ready.pop();
    order.push_back(units[k]);
    for (uint32_t d : dependants_of(k)) {
      if (--pending[d] == 0 && needed[d]) ready.push(d);
    }
  }
  // The original layer refines past the remesh, which a screen-space error
  // is measured against: a view with one never asks for it.
  if (screen.active) return order;
  std::vector<uint32_t> original;
  AppendOriginalLayer(layout, used, original);
  for (uint32_t id : original) {
    if (!held.Has({id, StreamUnit::kWholePacket}))
      order.push_back({id, StreamUnit::kWholePacket});
  }
  return order;
}

}  // namespace meshwave
