// What region requests need of a served mesh (docs/API.md, "Region
// requests"): its precincts, the numbering of its units, and where each
// part of a split packet lies in its payload. Built once per mesh, on the
// first region request (the precincts need the base mesh decoded and the
// hierarchy built: tens of milliseconds for a large mesh).
#ifndef MESHWAVE_SERVER_UNIT_TABLE_H_
#define MESHWAVE_SERVER_UNIT_TABLE_H_

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "meshwave/region_order.h"
#include "meshwave/status.h"
#include "meshwave/stream_header.h"
#include "meshwave/stream_units.h"

namespace meshwave::server {

class UnitTable {
 public:
  // ParseError when a split packet's part table does not parse.
  static Result<std::unique_ptr<const UnitTable>> Build(const StreamHeader& header,
                                                        const std::vector<std::string_view>& payloads);
  UnitTable(const UnitTable&) = delete;
  UnitTable& operator=(const UnitTable&) = delete;

  const StreamPrecincts& precincts() const { return precincts_; }
  // Nothing held: copy it to track what a client holds.
  const HeldUnits& nothing_held() const { return nothing_held_; }
  const UnitNumbering& numbering() const { return numbering_; }
  // PartLengths of every packet (empty for packets not split).
  const std::vector<std::vector<uint32_t>>& part_lengths() const { return part_lengths_; }
  // The bytes of `u` within its packet's payload.
  std::string_view Payload(std::string_view packet_payload, StreamUnit u) const;
  uint64_t Length(uint64_t packet_length, StreamUnit u) const;
  // Units of the subbands below `max_level` (-1: all) and the base refinement.
  size_t UnitsBelow(int max_level) const;

 private:
  UnitTable(StreamPrecincts precincts, const StreamHeader& header);
  StreamPrecincts precincts_;
  HeldUnits nothing_held_;
  UnitNumbering numbering_;
  std::vector<std::vector<uint32_t>> part_lengths_;
  std::vector<std::vector<uint32_t>> part_offsets_;  // from the payload's start
  std::vector<size_t> units_below_;                  // [max_level + 1]
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_UNIT_TABLE_H_
