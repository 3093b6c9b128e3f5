// Region-of-interest orders (issue 21): the units of a stream with
// precincts (docs/FORMAT.md 2.2) that refine a region first, then the
// rest, continuing from whatever the receiver already holds.
//
// A unit is a whole packet or one precinct's part of a split packet. The
// region order sends parts of split packets, never the packet whole, so a
// receiver that holds some parts is sent only the others.
#ifndef MESHWAVE_REGION_ORDER_H_
#define MESHWAVE_REGION_ORDER_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/region.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

struct StreamUnit {
  static constexpr uint32_t kWholePacket = 0xffffffffu;
  uint32_t id = 0;                // in the header's packet index
  uint32_t part = kWholePacket;  // a precinct of the packet's subband
  bool whole() const { return part == kWholePacket; }
  bool operator==(const StreamUnit&) const = default;
};

// Where a stream's precincts lie: per subband, each precinct's parent
// precinct, the ball around its base faces (the decoded base mesh, so a
// little off the final surface) and its share of the subband's
// coefficients. Derived from a validated header: the base mesh decoded and
// the hierarchy built (tens of milliseconds for a large mesh: build it once
// per stream).
class StreamPrecincts {
 public:
  static Result<StreamPrecincts> Create(const StreamHeader& header);

  int levels() const { return static_cast<int>(subbands_.size()); }
  uint32_t count(int j) const { return static_cast<uint32_t>(at(j).parent.size()); }
  uint32_t parent(int j, uint32_t p) const { return at(j).parent[p]; }
  const Vec3& centre(int j, uint32_t p) const { return at(j).centre[p]; }
  double radius(int j, uint32_t p) const { return at(j).radius[p]; }
  double share(int j, uint32_t p) const { return at(j).share[p]; }

 private:
  struct Subband {
    std::vector<uint32_t> parent;
    std::vector<Vec3> centre;
    std::vector<double> radius;
    std::vector<double> share;
  };
  const Subband& at(int j) const { return subbands_[static_cast<size_t>(j)]; }
  std::vector<Subband> subbands_;
};

// The units a receiver holds, and what each needs first: a packet needs
// what section 6 of FORMAT.md says (every part of a split dependency); a
// part its precinct's share one bitplane up and its parent precinct's at
// the same bitplane (3xC). The decoder keeps the same rules
// (ProgressiveDecoder::PartDependenciesMet).
class HeldUnits {
 public:
  HeldUnits(const StreamHeader& header, const StreamPrecincts& precincts);

  // 0 for a packet that is not split.
  uint32_t PartCount(uint32_t id) const;
  bool Has(StreamUnit u) const;
  // Not held, and everything it needs is.
  bool Ready(StreamUnit u) const;
  // Marks `u` held (a whole packet: all its parts). Does not check Ready.
  void Add(StreamUnit u);
  // Whether `u` names a unit of this stream (an id of the index; a part
  // below PartCount).
  bool Valid(StreamUnit u) const;
  size_t packet_count() const { return whole_.size(); }

 private:
  // Precinct p's share of packet id held: its part, or the whole packet.
  bool HasShare(uint32_t id, uint32_t p) const;

  const StreamPrecincts* precincts_;
  // Per packet: subband (-1: base refinement), bitplane, the packet one
  // bitplane up in its chain and the parent subband's at its bitplane
  // (3xC), -1 where there is none.
  std::vector<int> subband_, bitplane_, up_, parent_;
  std::vector<uint32_t> split_planes_;
  std::vector<char> whole_;
  std::vector<std::vector<char>> parts_;  // of split packets partly held
};

// The parts of split packet `id`, as views into its payload (docs/FORMAT.md
// 2.2); ParseError for a packet that is not split or a table that does not
// parse.
Result<std::vector<std::string_view>> PacketParts(const HeldUnits& units, uint32_t id,
                                                  std::string_view payload);
// The lengths of split packet `id`'s parts, from its payload (empty for a
// packet that is not split); ParseError for a table that does not parse.
Result<std::vector<uint32_t>> PartLengths(const HeldUnits& units, uint32_t id,
                                          std::string_view payload);

// The units `held` lacks, region first: greedily, among the units whose
// dependencies are held or sent before, those in the region (their
// precinct meets the sphere, or the view sees it) before the others, and
// among either the one with the largest estimated distortion reduction
// inside the region per byte. A part's reduction is
// its packet's (the header's estimate) in proportion to its bytes, weighted
// by RegionWeight of its precinct's ball; a whole packet's is weighted by
// its precincts' weights in proportion to their shares of the subband; the
// base refinement by subband 0's. Units of subbands at or above
// `max_level` (>= 0) are left out, as PacketOrder leaves them out.
// part_lengths[id]: PartLengths of every packet.
std::vector<StreamUnit> RegionOrder(const StreamHeader& header, const StreamPrecincts& precincts,
                                    std::span<const std::vector<uint32_t>> part_lengths,
                                    const Region& region, const HeldUnits& held,
                                    int max_level = -1);

}  // namespace meshwave

#endif  // MESHWAVE_REGION_ORDER_H_
