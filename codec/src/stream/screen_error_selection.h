// Which units a view with a screen-space error needs (the units RegionOrder
// keeps for a Region with screen_error_px; docs/API.md, "Region requests",
// step 7): by the stream's measured errors (meshwave/screen_errors.h) when
// given, else by the quantisers' bound.
#ifndef MESHWAVE_STREAM_SCREEN_ERROR_SELECTION_H_
#define MESHWAVE_STREAM_SCREEN_ERROR_SELECTION_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <variant>
#include <vector>

#include "meshwave/held_units.h"
#include "meshwave/region.h"
#include "meshwave/region_order.h"
#include "meshwave/screen_errors.h"
#include "meshwave/stream_header.h"
#include "stream/packet_index.h"

namespace meshwave {

// A screen-space error request (a view with Region::screen_error_px): a
// unit is needed when the error its precinct may still carry before it,
// projected at the precinct's nearest depth, exceeds the tolerance
// somewhere the view sees. The error bound of a subband holding its
// bitplanes above b: every coefficient not yet significant is below
// 2^(b+1) quantiser steps, and is reconstructed as 0 (Said and Pearlman's
// bound for bitplane coding, "A new, fast, and efficient image codec
// based on set partitioning in hierarchical trees", 1996); only the
// normal component where the stream codes in local frames, as a sliding
// of the surface along itself does not move what is drawn. The base
// refinement's before plane b: half of its grid, 2^(b+1) steps, per axis.
// With the stream's measured errors (meshwave/screen_errors.h) the error
// before a unit is measured, not bounded.
struct ScreenErrorSelection {
  bool active = false;
  double tolerance = 0;
  const StreamHeader* header = nullptr;
  // By measured errors: per subband and precinct, the rd prefix and the
  // lowest bitplane needed; for packets that travel whole, of all.
  const StreamScreenErrors* measured = nullptr;
  std::vector<std::vector<int>> need_rank, need_plane;  // [j][p]
  int whole_rank = 0, whole_plane = 0;
  // Per subband, per precinct: pixels per unit length (0 outside the view).
  std::vector<std::vector<double>> pixels;
  std::vector<double> subband_pixels;  // per subband, the largest

  static ScreenErrorSelection Of(
      const StreamHeader& header, const PacketLayout& layout,
      const StreamPrecincts& precincts,
      std::span<const std::vector<uint32_t>> part_lengths,
      const HeldUnits& held, const Region& region, int levels,
      const StreamScreenErrors* measured) {
    ScreenErrorSelection out;
    const auto* view = std::get_if<ViewRegion>(&region.shape);
    if (view == nullptr || !region.screen_error_px) return out;
    out.active = true;
    out.tolerance = *region.screen_error_px;
    out.header = &header;
    for (int j = 0; j < levels; ++j) {
      std::vector<double> row;
      double largest = 0;
      for (uint32_t p = 0; p < precincts.count(j); ++p) {
        const double w = RegionWeight(region, precincts.centre(j, p),
                                      precincts.radius(j, p));
        const double px = w > 0 ? PixelsPerUnit(*view, precincts.centre(j, p),
                                                precincts.radius(j, p))
                                : 0;
        row.push_back(px);
        largest = std::max(largest, px);
      }
      out.pixels.push_back(std::move(row));
      out.subband_pixels.push_back(largest);
    }
    if (measured && levels > 0 && measured->levels() == levels &&
        measured->finest_precincts() == precincts.count(levels - 1)) {
      out.Allocate(*measured, *view, header, layout, part_lengths, held);
    }
    return out;
  }

  // With measured errors: each cluster of the surface the view sees (a
  // base face) asks for the shortest prefix of the rd order, and for the
  // fewest bitplanes of every subband and the base refinement, that keep
  // its error, in pixels at its own depth, within the tolerance for good;
  // its neighbours ask as much (their coefficients move its border). Each
  // finest precinct then takes the cheaper of the two for all its
  // clusters. A unit is needed when the schedule of some finest precinct
  // below its own precinct holds it (a packet that travels whole: of any).
  void Allocate(const StreamScreenErrors& m, const ViewRegion& view,
                const StreamHeader& h,
                const PacketLayout& layout,
                std::span<const std::vector<uint32_t>> part_lengths,
                const HeldUnits& held) {
    const int levels = m.levels();
    const int finest = levels - 1;
    need_rank.assign(static_cast<size_t>(levels), {});
    need_plane.assign(static_cast<size_t>(levels), {});
    for (int j = 0; j < levels; ++j) {
      const size_t n = pixels[static_cast<size_t>(j)].size();
      need_rank[static_cast<size_t>(j)].assign(n, 0);
      need_plane[static_cast<size_t>(j)].assign(n, std::numeric_limits<int>::max());
    }
    whole_plane = std::numeric_limits<int>::max();
    constexpr int kNone = std::numeric_limits<int>::max();
    // Per finest precinct: the longest rd prefix and the lowest plane its
    // clusters, or the clusters around them, ask for.
    std::vector<int> rank(m.finest_precincts(), 0), plane(m.finest_precincts(), kNone);
    // RegionWeight's cone test and PixelsPerUnit without a trigonometric
    // call per cluster: a ball is seen when the cosine of the angle to its
    // centre is at least cos(cone + its angular radius).
    const Vec3 forward = view.direction.normalized();
    const double tan_half = std::tan(view.fov_degrees * std::numbers::pi / 360);
    const double aspect = static_cast<double>(view.width) / static_cast<double>(view.height);
    const double cone = std::atan(tan_half * std::sqrt(1 + aspect * aspect));
    const double cos_cone = std::cos(cone), sin_cone = std::sin(cone);
    const double half_height = 0.5 * static_cast<double>(view.height);
    // The error allowed at depth z is tolerance / px(z) = z * per_depth.
    const double per_depth = tolerance * tan_half / half_height;
    for (uint32_t c = 0; c < m.clusters(); ++c) {
      // Only where the view sees the cluster's precinct at all.
      if (!(pixels[static_cast<size_t>(finest)][m.Precinct(c)] > 0)) continue;
      const Vec3 to = m.centre(c) - view.eye;
      const double r = m.radius(c), along = to.dot(forward);
      const double distance2 = to.squaredNorm();
      if (distance2 > r * r) {
        // along >= cos_cone sqrt(d^2 - r^2) - sin_cone r, squared.
        const double lhs = along + sin_cone * r;
        if (lhs < 0 || lhs * lhs < cos_cone * cos_cone * (distance2 - r * r)) continue;
      }
      const double depth = along - r;
      const double allowed = depth > 0 ? depth * per_depth : 0;
      if (m.Error(0, c) <= allowed) continue;  // the header's base mesh does
      // Errors do not increase along either sequence: bisections.
      int k = 0;
      for (int hi = m.steps(); k < hi;) {
        const int mid = (k + hi) / 2;
        if (m.Error(mid, c) <= allowed) {
          hi = mid;
        } else {
          k = mid + 1;
        }
      }
      int b = m.planes();  // the largest plane within the tolerance
      for (int lo = 0; lo < b;) {
        const int mid = (lo + b + 1) / 2;
        if (m.PlaneError(mid, c) <= allowed) {
          lo = mid;
        } else {
          b = mid - 1;
        }
      }
      const uint32_t own = m.Precinct(c);
      rank[own] = std::max(rank[own], k);
      plane[own] = std::min(plane[own], b);
      for (uint32_t q : m.NeighbourPrecincts(c)) {
        rank[q] = std::max(rank[q], k);
        plane[q] = std::min(plane[q], b);
      }
    }
    // What packet id costs finest precinct q: its part of q's precinct, or
    // the packet; nothing once held.
    auto cost = [&](uint32_t id, uint32_t q) -> double {
      const int j = layout.Subband(id);
      const uint32_t p = j >= 0 ? m.Ancestor(j, q) : 0;
      const bool split = j >= 0 && id < part_lengths.size() && p < part_lengths[id].size();
      if (held.Has({id, StreamUnit::kWholePacket}) || (split && held.Has({id, p}))) return 0;
      return split ? part_lengths[id][p] : h.packets.length[id];
    };
    std::vector<uint32_t> geometry;  // every packet either schedule holds
    for (uint32_t id = 0; id < h.packets.length.size(); ++id) {
      if (m.Rank(id) >= 0) geometry.push_back(id);
    }
    for (uint32_t q = 0; q < m.finest_precincts(); ++q) {
      if (rank[q] == 0 && plane[q] == kNone) continue;
      double by_rank = 0, by_plane = 0;
      for (uint32_t id : geometry) {
        if (m.Rank(id) < rank[q]) by_rank += cost(id, q);
        if (layout.Bitplane(id) >= plane[q]) by_plane += cost(id, q);
      }
      const bool ranked = by_rank <= by_plane;
      for (int j = 0; j < levels; ++j) {
        const uint32_t p = m.Ancestor(j, q);
        if (ranked) {
          int& n = need_rank[static_cast<size_t>(j)][p];
          n = std::max(n, rank[q]);
        } else {
          int& n = need_plane[static_cast<size_t>(j)][p];
          n = std::min(n, plane[q]);
        }
      }
      if (ranked) {
        whole_rank = std::max(whole_rank, rank[q]);
      } else {
        whole_plane = std::min(whole_plane, plane[q]);
      }
    }
    measured = &m;
  }
  bool Holds(uint32_t id, int b, int rank, int plane) const {
    const int r = measured->Rank(id);
    return r >= 0 && (r < rank || b >= plane);
  }

  // The error bound of subband j before its bitplane b arrives.
  double ErrorBefore(int j, int b) const {
    const int components = header->transform.local_frames ? 1 : 3;
    double sum = 0;
    for (int c = 0; c < components; ++c) {
      const StreamHeader::Quantizer& q = header->quantizer(j, c);
      const double e = std::ldexp(q.step, std::min(b, q.top_bitplane) + 1);
      sum += e * e;
    }
    return std::sqrt(sum);
  }
  // A vertex carries the errors of every coarser level (interpolated) and
  // of its own: the tolerance is split, half to the finest subband, a
  // quarter to the next, and so on, the base the rest. A measured error
  // holds them all: the whole tolerance.
  double Share(int j) const {
    return std::ldexp(tolerance, j - static_cast<int>(subband_pixels.size()));
  }
  bool Exceeds(double error, double px, double tol) const {
    return px > 0 && error * px > tol;
  }
  // The packet `id` (of subband j, bitplane b), part p, or whole.
  bool PartNeeded(uint32_t id, int j, int b, uint32_t p) const {
    if (measured) {
      return Holds(id, b, need_rank[static_cast<size_t>(j)][p],
                   need_plane[static_cast<size_t>(j)][p]);
    }
    return Exceeds(ErrorBefore(j, b), pixels[static_cast<size_t>(j)][p],
                   Share(j));
  }
  bool PacketNeeded(uint32_t id, int j, int b) const {
    if (measured) return Holds(id, b, whole_rank, whole_plane);
    return Exceeds(ErrorBefore(j, b), subband_pixels[static_cast<size_t>(j)],
                   Share(j));
  }
  // The base moves every vertex: judged where the view sees most detail
  // (a stream without subbands: always needed).
  bool BaseNeeded(uint32_t id, int plane) const {
    if (subband_pixels.empty()) return true;
    if (measured) return PacketNeeded(id, 0, plane);
    const double px =
        *std::max_element(subband_pixels.begin(), subband_pixels.end());
    return Exceeds(std::sqrt(3.0) * std::ldexp(header->base.step, plane), px,
                   Share(-1));
  }
};

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_SCREEN_ERROR_SELECTION_H_
