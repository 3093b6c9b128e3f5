// Reading the protobuf wire format (protobuf.dev/programming-guides/encoding)
// without the protobuf library: a bounded reader of records, skipping of
// unknown fields and groups, and readers of the field types, each with the
// rule protobuf 3.21's parser applies (parse_context.h, wire_format_lite.h),
// so that a message read with them accepts and refuses the bytes protobuf
// does. ReadStreamHeader (stream/stream_header_reader.cpp) reads the
// decoder's one message with them; the writing side is core/protobuf_wire.h.
#ifndef MESHWAVE_CORE_PROTOBUF_WIRE_READER_H_
#define MESHWAVE_CORE_PROTOBUF_WIRE_READER_H_

#include <climits>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/protobuf_wire.h"

namespace meshwave::wire {

// Reads records from the front of a message's bytes; every read checks
// that the bytes are there and returns false when they are not.
class WireReader {
 public:
  explicit WireReader(std::string_view bytes) : rest_(bytes) {}

  bool done() const { return rest_.empty(); }
  const char* position() const { return rest_.data(); }

  // Up to 10 bytes; bits beyond 64 are dropped (as protobuf does).
  bool Varint(uint64_t& value) {
    value = 0;
    for (int i = 0; i < 10 && i < static_cast<int>(rest_.size()); ++i) {
      const auto byte = static_cast<uint8_t>(rest_[static_cast<size_t>(i)]);
      value |= static_cast<uint64_t>(byte & 0x7f) << (7 * i);
      if (byte < 0x80) {
        rest_.remove_prefix(static_cast<size_t>(i) + 1);
        return true;
      }
    }
    return false;
  }
  // A tag is a varint of at most 5 bytes, kept modulo 2^32.
  bool Tag(uint32_t& tag) {
    uint64_t value = 0;
    for (int i = 0; i < 5 && i < static_cast<int>(rest_.size()); ++i) {
      const auto byte = static_cast<uint8_t>(rest_[static_cast<size_t>(i)]);
      value |= static_cast<uint64_t>(byte & 0x7f) << (7 * i);
      if (byte < 0x80) {
        rest_.remove_prefix(static_cast<size_t>(i) + 1);
        tag = static_cast<uint32_t>(value);
        return true;
      }
    }
    return false;
  }
  bool Fixed64(uint64_t& value) { return Fixed(value); }
  bool Fixed32(uint32_t& value) { return Fixed(value); }
  // Little-endian, whatever the host.
  template <class T>
  bool Fixed(T& value) {
    if (rest_.size() < sizeof(T)) return false;
    value = 0;
    for (size_t i = 0; i < sizeof(T); ++i) {
      value |= static_cast<T>(static_cast<uint8_t>(rest_[i])) << (8 * i);
    }
    rest_.remove_prefix(sizeof(T));
    return true;
  }
  // A length: at most 5 bytes and below 2^31 - 16 (protobuf's ReadSize),
  // then that many bytes must follow.
  bool Delimited(std::string_view& out) {
    uint64_t size = 0;
    int i = 0;
    for (;; ++i) {
      if (i == 5 || i >= static_cast<int>(rest_.size())) return false;
      const auto byte = static_cast<uint8_t>(rest_[static_cast<size_t>(i)]);
      if (i == 4 && byte >= 8) return false;
      size |= static_cast<uint64_t>(byte & 0x7f) << (7 * i);
      if (byte < 0x80) break;
    }
    if (size > static_cast<uint64_t>(INT_MAX - 16)) return false;
    rest_.remove_prefix(static_cast<size_t>(i) + 1);
    if (size > rest_.size()) return false;
    out = rest_.substr(0, size);
    rest_.remove_prefix(size);
    return true;
  }

 private:
  std::string_view rest_;
};

inline bool SkipField(uint32_t tag, WireReader& r, int depth);

// A group's fields up to the end-group tag matching `start_tag`.
inline bool SkipGroup(uint32_t start_tag, WireReader& r, int depth) {
  if (--depth < 0) return false;
  while (!r.done()) {
    uint32_t tag = 0;
    if (!r.Tag(tag) || tag == 0) return false;
    if ((tag & 7) == kEndGroup) return tag == start_tag + 1;
    if (!SkipField(tag, r, depth)) return false;
  }
  return false;  // no end-group tag
}

// A field the message does not know (or knows with another wire type):
// skipped, as protobuf keeps it aside among the unknown fields.
inline bool SkipField(uint32_t tag, WireReader& r, int depth) {
  if ((tag >> 3) == 0) return false;
  uint64_t u64 = 0;
  uint32_t u32 = 0;
  std::string_view bytes;
  switch (tag & 7) {
    case kVarint: return r.Varint(u64);
    case kFixed64: return r.Fixed64(u64);
    case kLengthDelimited: return r.Delimited(bytes);
    case kStartGroup: return SkipGroup(tag, r, depth);
    case kFixed32: return r.Fixed32(u32);
    default: return false;  // 6 and 7 do not exist
  }
}

// What a message's field reader did with one record.
enum class Field { kRead, kUnknown, kError };

// Reads the fields of one message, handing each record to `read`;
// `on_record(tag, begin, end, known)` sees every record's bytes (the header
// uses it to drop `present`). A message ends with its bytes: a zero or
// end-group tag inside it is an error.
template <class Read, class OnRecord>
bool ReadMessage(std::string_view bytes, int depth, Read&& read, OnRecord&& on_record) {
  WireReader r(bytes);
  while (!r.done()) {
    const char* begin = r.position();
    uint32_t tag = 0;
    if (!r.Tag(tag) || tag == 0 || (tag & 7) == kEndGroup) return false;
    const Field f = read(tag >> 3, tag & 7, r, depth);
    if (f == Field::kError) return false;
    if (f == Field::kUnknown && !SkipField(tag, r, depth)) return false;
    on_record(tag, begin, r.position(), f == Field::kRead);
  }
  return true;
}

template <class Read>
bool ReadMessage(std::string_view bytes, int depth, Read&& read) {
  return ReadMessage(bytes, depth, read, [](uint32_t, const char*, const char*, bool) {});
}

// Embedded messages are one level deeper.
template <class Read>
Field ReadEmbedded(WireReader& r, int depth, Read&& read) {
  std::string_view bytes;
  if (!r.Delimited(bytes) || depth - 1 < 0) return Field::kError;
  return ReadMessage(bytes, depth - 1, read) ? Field::kRead : Field::kError;
}

inline Field ReadU64(uint32_t type, WireReader& r, uint64_t& out) {
  if (type != kVarint) return Field::kUnknown;
  return r.Varint(out) ? Field::kRead : Field::kError;
}

// uint32, int32 and enum fields keep the varint's low 32 bits.
template <class T>
Field ReadVarint32(uint32_t type, WireReader& r, T& out) {
  uint64_t v = 0;
  const Field f = ReadU64(type, r, v);
  if (f == Field::kRead) out = static_cast<T>(static_cast<int32_t>(static_cast<uint32_t>(v)));
  return f;
}

inline Field ReadBool(uint32_t type, WireReader& r, bool& out) {
  uint64_t v = 0;
  const Field f = ReadU64(type, r, v);
  if (f == Field::kRead) out = v != 0;
  return f;
}

inline Field ReadDouble(uint32_t type, WireReader& r, double& out) {
  if (type != kFixed64) return Field::kUnknown;
  uint64_t bits = 0;
  if (!r.Fixed64(bits)) return Field::kError;
  std::memcpy(&out, &bits, sizeof out);
  return Field::kRead;
}

inline Field ReadFloat(uint32_t type, WireReader& r, float& out) {
  if (type != kFixed32) return Field::kUnknown;
  uint32_t bits = 0;
  if (!r.Fixed32(bits)) return Field::kError;
  std::memcpy(&out, &bits, sizeof out);
  return Field::kRead;
}

inline Field ReadFixed32(uint32_t type, WireReader& r, uint32_t& out) {
  if (type != kFixed32) return Field::kUnknown;
  return r.Fixed32(out) ? Field::kRead : Field::kError;
}

inline Field ReadBytes(uint32_t type, WireReader& r, std::string& out) {
  if (type != kLengthDelimited) return Field::kUnknown;
  std::string_view bytes;
  if (!r.Delimited(bytes)) return Field::kError;
  out.assign(bytes);
  return Field::kRead;
}

// Repeated double or float: one value per record, or a packed run whose
// length must be a multiple of the value's size.
template <class T>
Field ReadRepeatedFixed(uint32_t type, WireReader& r, std::vector<T>& out) {
  static_assert(sizeof(T) == 8 || sizeof(T) == 4);
  using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
  constexpr uint32_t kOne = sizeof(T) == 8 ? kFixed64 : kFixed32;
  T value;
  if (type == kOne) {
    Bits bits = 0;
    if (!r.Fixed(bits)) return Field::kError;
    std::memcpy(&value, &bits, sizeof value);
    out.push_back(value);
    return Field::kRead;
  }
  if (type != kLengthDelimited) return Field::kUnknown;
  std::string_view packed;
  if (!r.Delimited(packed) || packed.size() % sizeof(T) != 0) return Field::kError;
  WireReader values(packed);
  while (!values.done()) {
    Bits bits = 0;
    values.Fixed(bits);
    std::memcpy(&value, &bits, sizeof value);
    out.push_back(value);
  }
  return Field::kRead;
}

// Repeated uint32: one varint per record, or a packed run of varints that
// must end exactly with the run.
inline Field ReadRepeatedU32(uint32_t type, WireReader& r, std::vector<uint32_t>& out) {
  uint64_t v = 0;
  if (type == kVarint) {
    if (!r.Varint(v)) return Field::kError;
    out.push_back(static_cast<uint32_t>(v));
    return Field::kRead;
  }
  if (type != kLengthDelimited) return Field::kUnknown;
  std::string_view packed;
  if (!r.Delimited(packed)) return Field::kError;
  WireReader values(packed);
  while (!values.done()) {
    if (!values.Varint(v)) return Field::kError;
    out.push_back(static_cast<uint32_t>(v));
  }
  return Field::kRead;
}

}  // namespace meshwave::wire

#endif  // MESHWAVE_CORE_PROTOBUF_WIRE_READER_H_
