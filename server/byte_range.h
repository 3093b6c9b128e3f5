// The Range request header (RFC 9110, section 14) against one resource of
// known size: which bytes to send, or why not.
#ifndef MESHWAVE_SERVER_BYTE_RANGE_H_
#define MESHWAVE_SERVER_BYTE_RANGE_H_

#include <cstdint>
#include <string>
#include <string_view>

namespace meshwave::server {

struct RangeRequest {
  enum Kind {
    kFull,           // no usable Range: send everything (200)
    kPartial,        // one range to send: 206
    kUnsatisfiable,  // 416 with Content-Range: bytes */size
  } kind = kFull;
  uint64_t first = 0, last = 0;  // inclusive, when kPartial
  std::string problem;           // kUnsatisfiable: what is wrong, for the client
};

// Parses `ranges-specifier` (14.1.1) for a resource of `size` bytes:
// - the unit is compared case-insensitively; a unit other than "bytes" is
//   ignored (kFull), as 14.2 requires;
// - the range set is a list (RFC 9110 5.6.1): empty elements and optional
//   whitespace around commas and around the whole set are accepted;
// - each element is `first-last`, `first-` or `-suffix` in decimal digits;
//   numbers too large for 64 bits saturate (14.1.1 warns of overflows);
// - an element of another shape, or whose last position is before its
//   first, makes the specifier invalid: kUnsatisfiable with `problem` set
//   (14.2 lets a server reject an invalid specifier);
// - the satisfiable ranges (first < size; suffix > 0 on a non-empty
//   resource) are coalesced when they overlap or touch (14.2 allows it):
//   one range left gives kPartial; several disjoint ones give kFull (no
//   multipart responses, and a server may ignore Range); none gives
//   kUnsatisfiable;
// - more than kMaxRanges elements give kFull (14.2: a sign of abuse).
RangeRequest ParseRange(std::string_view header, uint64_t size);

inline constexpr int kMaxRanges = 64;

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_BYTE_RANGE_H_
