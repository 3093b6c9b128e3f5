// The units of a stream and what each needs first: the one home of the unit
// and part dependency rules (docs/FORMAT.md, sections 2.2 and 6). The
// decoder keeps its held set in one (ProgressiveDecoder::held()), the
// server tracks what a client holds in one, and a client's held bitmap
// (meshwave/stream_units.h) is read into one, so that decoder, client and
// server cannot disagree about what a stream is.
//
// A unit is a whole packet or one precinct's part of a split packet.
#ifndef MESHWAVE_HELD_UNITS_H_
#define MESHWAVE_HELD_UNITS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshwave/stream_header.h"

namespace meshwave {

struct StreamUnit {
  static constexpr uint32_t kWholePacket = 0xffffffffu;
  uint32_t id = 0;               // in the header's packet index
  uint32_t part = kWholePacket;  // a precinct of the packet's subband
  bool whole() const { return part == kWholePacket; }
  bool operator==(const StreamUnit&) const = default;
};

// Per subband, the parent precinct of each of its precincts in the subband
// above (subband 0's: 0); each list's length is the subband's precinct
// count. Derived from the header's precinct partition.
using PrecinctParents = std::vector<std::vector<uint32_t>>;

// The units held of one stream, and the rules: a whole packet needs the
// packet one bitplane up in its subband (or in the base refinement) and,
// with 3xC, the parent subband's packet at the same bitplane, each whole
// (every part of a split one); a part needs its precinct's share of the
// packet one bitplane up and, with 3xC, its parent precinct's share of the
// parent subband's packet at the same bitplane (a share: that part, or the
// packet whole where it is not split). A texture packet needs nothing; a
// part of the original layer needs the part before it.
class HeldUnits {
 public:
  // `header` validated (ValidateStreamHeader); `parents` from its
  // partition. Nothing held.
  HeldUnits(const StreamHeader& header, PrecinctParents parents);

  size_t packet_count() const { return whole_.size(); }
  // How many parts packet `id` travels in (0: not split).
  uint32_t PartCount(uint32_t id) const;
  // Whether `u` names a unit of this stream: an id of the index, a part
  // below PartCount.
  bool Valid(StreamUnit u) const;
  bool Has(StreamUnit u) const;
  // The first packet `u` needs a share of that is not held (the one a
  // bitplane up before the parent subband's), -1 when none is missing or
  // `u` is not Valid.
  int64_t FirstMissing(StreamUnit u) const;
  // Valid and everything it needs held (held or not itself).
  bool DependenciesMet(StreamUnit u) const { return Valid(u) && FirstMissing(u) < 0; }
  // Not held, and everything it needs is.
  bool Ready(StreamUnit u) const { return DependenciesMet(u) && !Has(u); }
  // Marks `u` held (a whole packet: all its parts; the last part of a
  // packet: the packet whole). Checks Valid only, not Ready.
  void Add(StreamUnit u);
  // Nothing held.
  void Clear();

 private:
  // Precinct p's share of packet id held: its part, or the whole packet.
  bool HasShare(uint32_t id, uint32_t p) const;

  PrecinctParents parents_;
  // Per packet: subband (-1: base refinement), the packet one bitplane up
  // in its chain and the parent subband's at its bitplane (3xC), -1 where
  // there is none, and its part count.
  std::vector<int> subband_, up_, parent_;
  std::vector<uint32_t> part_count_;
  std::vector<char> whole_;
  std::vector<std::vector<char>> parts_;  // of split packets partly held
};

}  // namespace meshwave

#endif  // MESHWAVE_HELD_UNITS_H_
