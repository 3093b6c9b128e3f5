// Single byte ranges of the Range request header (RFC 9110 14.2).
#ifndef MESHWAVE_SERVER_BYTE_RANGE_H_
#define MESHWAVE_SERVER_BYTE_RANGE_H_

#include <cstdint>
#include <string_view>

namespace meshwave::server {

struct RangeRequest {
  enum Kind {
    kFull,           // no usable Range: send everything (200)
    kPartial,        // one satisfiable range: 206
    kUnsatisfiable,  // 416 with Content-Range: bytes */size
  } kind = kFull;
  uint64_t first = 0, last = 0;  // inclusive, when kPartial
};

// "bytes=a-b", "bytes=a-", "bytes=-n" against a resource of `size` bytes.
// Other units and several ranges give kFull (the server may ignore Range);
// malformed numbers and ranges starting past the end give kUnsatisfiable.
RangeRequest ParseRange(std::string_view header, uint64_t size);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_BYTE_RANGE_H_
