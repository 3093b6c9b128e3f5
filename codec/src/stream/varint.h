// Protobuf base-128 varints (protobuf.dev/programming-guides/encoding): the
// container writer appends the `present` list with them and the sizes of
// containers are added up from their lengths.
#ifndef MESHWAVE_STREAM_VARINT_H_
#define MESHWAVE_STREAM_VARINT_H_

#include <cstdint>
#include <string>

namespace meshwave {

inline uint64_t VarintSize(uint64_t v) {
  uint64_t n = 1;
  while (v >= 0x80) {
    v >>= 7;
    ++n;
  }
  return n;
}

inline void PutVarint(std::string& out, uint64_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<char>((v & 0x7f) | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<char>(v));
}

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_VARINT_H_
