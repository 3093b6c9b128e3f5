// The protobuf wire format (protobuf.dev/programming-guides/encoding) for the
// few places that write or read it without the protobuf library: the decoder
// library (no protobuf, for WebAssembly) reading the header (with
// core/protobuf_wire_reader.h) and appending the container's `present` list,
// the unit records of region streams, and the server writing a packet
// message's prefix without copying the payload. Field numbers come from the .proto:
// generated kFooFieldNumber constants where protobuf is linked, constants
// pinned to those by a test elsewhere.
#ifndef MESHWAVE_CORE_PROTOBUF_WIRE_H_
#define MESHWAVE_CORE_PROTOBUF_WIRE_H_

#include <cstdint>
#include <string>

namespace meshwave {

enum WireType : uint32_t {
  kVarint = 0,
  kFixed64 = 1,
  kLengthDelimited = 2,
  kStartGroup = 3,
  kEndGroup = 4,
  kFixed32 = 5,
};

// A field's key: its number and wire type.
constexpr uint32_t WireTag(uint32_t field, WireType wire) { return field << 3 | wire; }

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

#endif  // MESHWAVE_CORE_PROTOBUF_WIRE_H_
