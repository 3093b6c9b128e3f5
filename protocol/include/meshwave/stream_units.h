// The two wire forms of a stream's units (meshwave/held_units.h) that
// clients and the server exchange (docs/API.md, "Region requests"): the set
// of units a client holds, as a bitmap over unit numbers in base64url, and
// the unit records of a region stream's HTTP body.
#ifndef MESHWAVE_STREAM_UNITS_H_
#define MESHWAVE_STREAM_UNITS_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/held_units.h"
#include "meshwave/status.h"

namespace meshwave {

// Units numbered packet by packet in id order: a packet that is not split
// is one unit, a split packet one per part, in precinct order.
class UnitNumbering {
 public:
  explicit UnitNumbering(const HeldUnits& units);
  size_t size() const { return units_.size(); }
  StreamUnit unit(size_t n) const { return units_[n]; }
  // The number of a unit of this stream (HeldUnits::Valid; not a whole
  // split packet, which is several units).
  size_t number(StreamUnit u) const { return first_[u.id] + (u.whole() ? 0 : u.part); }

 private:
  std::vector<StreamUnit> units_;
  std::vector<size_t> first_;  // per packet id
};

// The held set's bitmap: bit n (byte n / 8, bit n % 8, least significant
// first) set when unit n is held; trailing zero bytes left out; base64url
// without padding. "" for nothing held.
std::string EncodeHeldUnits(const HeldUnits& held, const UnitNumbering& numbering);

// Adds the units `text` names to `held`. kInvalidArgument, naming the
// problem, for text that is not base64url, a bit past the last unit, or a
// set not closed under the dependencies (a unit held without what it
// needs: a decoder could not have decoded it).
Status DecodeHeldUnits(std::string_view text, const UnitNumbering& numbering, HeldUnits& held);

// One unit record: the packet id, 0 for a whole packet or 1 + the part, the
// payload's length (varints, LEB128), then the payload.
void AppendUnitRecord(std::string& out, StreamUnit unit, std::string_view payload);

// Reads unit records from a body that arrives in pieces. Every record is
// handed to `on_unit` whole; an error from it stops the reader and is
// returned. ParseError for a varint longer than 5 bytes or above 2^32 - 1,
// and for a length above `max_payload`.
class UnitRecordReader {
 public:
  using Handler = std::function<Status(StreamUnit, std::string_view payload)>;
  UnitRecordReader(uint64_t max_payload, Handler on_unit)
      : max_payload_(max_payload), on_unit_(std::move(on_unit)) {}
  Status Feed(std::string_view bytes);
  // No record started and not finished: the body may end here.
  bool at_boundary() const { return buffer_.empty(); }
  size_t records() const { return records_; }

 private:
  uint64_t max_payload_;
  Handler on_unit_;
  std::string buffer_;  // an unfinished record
  size_t records_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_UNITS_H_
