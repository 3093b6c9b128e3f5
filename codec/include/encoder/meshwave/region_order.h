// Region-of-interest orders: the units of a stream with precincts
// (docs/FORMAT.md 2.2; meshwave/held_units.h) that refine a region first,
// then the rest, continuing from whatever the receiver already holds. The
// region order sends parts of split packets, never the packet whole, so a
// receiver that holds some parts is sent only the others.
#ifndef MESHWAVE_REGION_ORDER_H_
#define MESHWAVE_REGION_ORDER_H_

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "meshwave/held_units.h"
#include "meshwave/mesh.h"
#include "meshwave/region.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"

namespace meshwave {

class StreamScreenErrors;

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
  uint32_t count(int j) const {
    return static_cast<uint32_t>(at(j).parent.size());
  }
  uint32_t parent(int j, uint32_t p) const { return at(j).parent[p]; }
  const Vec3& centre(int j, uint32_t p) const { return at(j).centre[p]; }
  double radius(int j, uint32_t p) const { return at(j).radius[p]; }
  double share(int j, uint32_t p) const { return at(j).share[p]; }
  // Every precinct's parent, as HeldUnits takes them.
  PrecinctParents parents() const;

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

// The parts of split packet `id`, as views into its payload (docs/FORMAT.md
// 2.2); ParseError for a packet that is not split or a table that does not
// parse.
Result<std::vector<std::string_view>> PacketParts(const HeldUnits& units,
                                                  uint32_t id,
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
// base refinement by subband 0's. Texture levels are global: counted
// inside the region, valued as the rd order values them, each after the
// level before. Units of subbands at or above
// `max_level` (>= 0) are left out, as PacketOrder leaves them out.
// part_lengths[id]: PartLengths of every packet.
//
// A view with a screen-space error (Region::screen_error_px) stops where
// the view needs nothing more: only the units whose precinct's error
// bound before them, in pixels at the precinct's nearest depth, exceeds
// the subband's share of the tolerance where the view sees it (half to the
// finest subband, a quarter to the next, ..., the base refinement the
// rest), with what they need; never the original layer (the tolerance is
// measured against the remesh). Texture levels are sent as above.
// With `measured` (meshwave/screen_errors.h, of the same stream), units
// are judged by measured errors instead: each base face the view sees asks
// for the shortest rd prefix and for the fewest bitplanes that keep its
// measured error, in pixels at its own depth, within the tolerance (its
// neighbouring faces ask as much); each finest precinct takes the cheaper
// of the two for all its faces, and a unit is needed when the schedule of
// some finest precinct within its precinct holds it. `meshwave view-rd`
// measures what such requests bring.
std::vector<StreamUnit> RegionOrder(
    const StreamHeader& header, const StreamPrecincts& precincts,
    std::span<const std::vector<uint32_t>> part_lengths, const Region& region,
    const HeldUnits& held, int max_level = -1,
    const StreamScreenErrors* measured = nullptr);

}  // namespace meshwave

#endif  // MESHWAVE_REGION_ORDER_H_
