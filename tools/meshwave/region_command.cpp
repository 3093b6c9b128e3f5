// meshwave region-rd STREAM.mwv: how much sooner the region order (issue
// 21, meshwave/region_order.h) refines a region than the uniform rd order.
//
// For each region (--region, or spheres around a few finest vertices
// holding --shares of the finest vertices): the region's PSNR at some
// budgets in both orders, and the bytes each order needs before the
// region's vertices are exactly those of the complete stream.
// PSNR: vertex PSNR of the vertices inside the sphere against the
// complete stream's decoded mesh (what both orders converge to), peak =
// the header's bounding-box diagonal. Bytes: payload bytes (the header,
// the same for both, excluded).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "complete_stream.h"
#include "meshwave/container.h"
#include "meshwave/progression.h"
#include "meshwave/progressive_decoder.h"
#include "meshwave/region.h"
#include "meshwave/region_order.h"
#include "meshwave/region_text.h"

namespace meshwave::cli {
namespace {

struct RegionArgs {
  std::string file;
  std::string region;
  std::string shares = "0.05,0.1,0.25";
  int seeds = 3;
};

using Stream = CompleteStream;

double RegionPsnr(const Stream& s, const std::vector<Vec3>& got,
                  const SphereRegion& r) {
  double sse = 0;
  size_t n = 0;
  for (size_t v = 0; v < s.full.size(); ++v) {
    if ((s.full[v] - r.centre).norm() > r.radius) continue;
    sse += (got[v] - s.full[v]).squaredNorm();
    ++n;
  }
  if (n == 0) return std::nan("");
  return sse == 0 ? INFINITY
                  : 20 * std::log10(s.diagonal /
                                    std::sqrt(sse / static_cast<double>(n)));
}

// The region PSNR after the first `count` units of `order`.
Result<double> PsnrAfter(const Stream& s, ProgressiveDecoder& d,
                         const std::vector<StreamUnit>& order, size_t count,
                         const SphereRegion& r) {
  d.Reset();
  for (size_t k = 0; k < count; ++k) MW_RETURN_IF_ERROR(s.Send(d, order[k]));
  return RegionPsnr(s, d.Positions(), r);
}

// Payload bytes of the first `count` units.
uint64_t BytesOf(const Stream& s, const std::vector<StreamUnit>& order,
                 size_t count) {
  uint64_t bytes = 0;
  for (size_t k = 0; k < count; ++k) bytes += s.UnitBytes(order[k]);
  return bytes;
}

// The longest prefix within `budget` payload bytes.
size_t PrefixWithin(const Stream& s, const std::vector<StreamUnit>& order,
                    uint64_t budget) {
  uint64_t bytes = 0;
  size_t k = 0;
  for (; k < order.size(); ++k) {
    bytes += s.UnitBytes(order[k]);
    if (bytes > budget) break;
  }
  return k;
}

// The shortest prefix after which the region's vertices are exactly the
// complete stream's (bisection: once exact, a longer prefix stays exact).
Result<size_t> PrefixExact(const Stream& s, ProgressiveDecoder& d,
                           const std::vector<StreamUnit>& order,
                           const SphereRegion& r) {
  size_t lo = 0, hi = order.size();
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    MW_ASSIGN_OR_RETURN(double psnr, PsnrAfter(s, d, order, mid, r));
    if (std::isinf(psnr)) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return lo;
}

// Spheres around the finest vertices farthest along a few fixed directions
// (deterministic), each holding `share` of the finest vertices.
std::vector<SphereRegion> AutoRegions(const Stream& s, double share,
                                      int seeds) {
  static const Vec3 kDirections[] = {
      Vec3(0.31, 0.85, 0.42), Vec3(-0.77, 0.12, 0.63), Vec3(0.2, -0.6, -0.77),
      Vec3(0.9, -0.3, 0.3), Vec3(-0.4, -0.5, 0.77)};
  std::vector<SphereRegion> out;
  for (int k = 0; k < seeds && k < 5; ++k) {
    const Vec3 d = kDirections[k].normalized();
    size_t best = 0;
    for (size_t v = 0; v < s.full.size(); ++v) {
      if (s.full[v].dot(d) > s.full[best].dot(d)) best = v;
    }
    std::vector<double> distance;
    distance.reserve(s.full.size());
    for (const Vec3& p : s.full) distance.push_back((p - s.full[best]).norm());
    const size_t nth = std::min(
        distance.size() - 1,
        static_cast<size_t>(share * static_cast<double>(distance.size())));
    std::nth_element(distance.begin(),
                     distance.begin() + static_cast<std::ptrdiff_t>(nth),
                     distance.end());
    out.push_back({s.full[best], distance[nth]});
  }
  return out;
}

Status Run(const RegionArgs& args) {
  MW_ASSIGN_OR_RETURN(std::unique_ptr<Stream> loaded,
                      LoadCompleteStream(args.file, "region-rd"));
  const Stream& s = *loaded;
  const StreamHeader& h = s.header();
  struct Case {
    std::string label;
    SphereRegion sphere;
  };
  std::vector<Case> cases;
  if (!args.region.empty()) {
    MW_ASSIGN_OR_RETURN(Region r, ParseSphereRegion(args.region));
    cases.push_back({"--region", std::get<SphereRegion>(r.shape)});
  } else {
    std::stringstream list(args.shares);
    std::string item;
    while (std::getline(list, item, ',')) {
      double share = 0;
      try {
        share = std::stod(item);
      } catch (...) {
        return InvalidArgument("--shares: \"" + item + "\" is not a number");
      }
      if (!(share > 0 && share < 1))
        return InvalidArgument("--shares: each in (0, 1)");
      int k = 0;
      for (const SphereRegion& r : AutoRegions(s, share, args.seeds)) {
        char label[32];
        std::snprintf(label, sizeof label, "%g%% #%d", 100 * share, ++k);
        cases.push_back({label, r});
      }
    }
  }
  uint64_t total = 0;
  for (std::string_view p : s.payload) total += p.size();
  std::vector<StreamUnit> rd;
  for (uint32_t id : PacketOrder(h, Progression::kRd))
    rd.push_back({id, StreamUnit::kWholePacket});
  MW_ASSIGN_OR_RETURN(auto decoder, ProgressiveDecoder::Create(h));
  std::printf(
      "%s: %zu finest vertices, %llu payload bytes; region PSNR (dB, vertices "
      "in the "
      "sphere against the complete stream's mesh) rd / region order\n",
      args.file.c_str(), s.full.size(), static_cast<unsigned long long>(total));
  std::printf("%-10s %8s %15s %15s %15s   %s\n", "region", "vertices",
              "at 10 %", "at 25 %", "at 50 %",
              "bytes until the region is exact: rd / region (ratio)");
  for (const Case& c : cases) {
    const HeldUnits none(h, s.precincts->parents());
    const Region region{c.sphere, std::nullopt};
    const std::vector<StreamUnit> by_region =
        RegionOrder(h, *s.precincts, s.part_lengths, region, none);
    size_t inside = 0;
    for (const Vec3& p : s.full)
      inside += (p - c.sphere.centre).norm() <= c.sphere.radius;
    std::string cells;
    for (double share : {0.10, 0.25, 0.50}) {
      const auto budget =
          static_cast<uint64_t>(share * static_cast<double>(total));
      MW_ASSIGN_OR_RETURN(
          double a,
          PsnrAfter(s, *decoder, rd, PrefixWithin(s, rd, budget), c.sphere));
      MW_ASSIGN_OR_RETURN(
          double b, PsnrAfter(s, *decoder, by_region,
                              PrefixWithin(s, by_region, budget), c.sphere));
      char cell[40];
      std::snprintf(cell, sizeof cell, " %6.2f / %6.2f", a, b);
      cells += cell;
    }
    MW_ASSIGN_OR_RETURN(size_t rd_count,
                        PrefixExact(s, *decoder, rd, c.sphere));
    MW_ASSIGN_OR_RETURN(size_t region_count,
                        PrefixExact(s, *decoder, by_region, c.sphere));
    const uint64_t rd_bytes = BytesOf(s, rd, rd_count);
    const uint64_t region_bytes = BytesOf(s, by_region, region_count);
    std::printf("%-10s %8zu%s   %llu / %llu (%.2f)\n", c.label.c_str(), inside,
                cells.c_str(), static_cast<unsigned long long>(rd_bytes),
                static_cast<unsigned long long>(region_bytes),
                rd_bytes > 0 ? static_cast<double>(region_bytes) /
                                   static_cast<double>(rd_bytes)
                             : 0.0);
  }
  return Status::Ok();
}

}  // namespace

void AddRegionCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<RegionArgs>();
  CLI::App* cmd =
      app.add_subcommand("region-rd",
                         "How much sooner the region order refines a region "
                         "than the uniform rd order, on a "
                         "complete .mwv stream: the region's PSNR at 10, 25 "
                         "and 50 % of the payload bytes in "
                         "both orders, and the bytes each needs before the "
                         "region is exactly the complete "
                         "stream's");
  cmd->add_option("stream", args->file,
                  "A complete .mwv stream (meshwave encode)")
      ->required();
  cmd->add_option("--region", args->region,
                  "A sphere x,y,z,r (default: spheres chosen by --shares)");
  cmd->add_option("--shares", args->shares,
                  "Comma-separated shares of the finest vertices each "
                  "automatic sphere holds")
      ->capture_default_str();
  cmd->add_option("--seeds", args->seeds,
                  "Automatic spheres per share (around the vertices "
                  "farthest along fixed directions)")
      ->check(CLI::Range(1, 5))
      ->capture_default_str();
  cmd->callback([args, &exit_code] {
    if (Status s = Run(*args); !s.ok()) exit_code = Fail("region-rd", s);
  });
}

}  // namespace meshwave::cli
