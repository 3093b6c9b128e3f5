// ReadStreamHeader: the protobuf wire format (protobuf.dev/programming-guides/
// encoding) for the one message the decoder needs. Each rule below is the
// one protobuf 3.21's parser applies (parse_context.h, wire_format_lite.h),
// so both accept and refuse the same bytes; tests/fuzz/stream_header_fuzz.cpp
// compares them.
#include <climits>
#include <cstring>
#include <type_traits>

#include "core/protobuf_wire.h"
#include "meshwave/stream_header.h"
#include "stream/stream_format.h"
#include "stream/utf8.h"

namespace meshwave {
namespace {

// Protobuf's default recursion limit: embedded messages and groups nest at
// most this deep below the header.
constexpr int kMaxDepth = 100;

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

bool SkipField(uint32_t tag, WireReader& r, int depth);

// A group's fields up to the end-group tag matching `start_tag`.
bool SkipGroup(uint32_t start_tag, WireReader& r, int depth) {
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
bool SkipField(uint32_t tag, WireReader& r, int depth) {
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

Field ReadU64(uint32_t wire, WireReader& r, uint64_t& out) {
  if (wire != kVarint) return Field::kUnknown;
  return r.Varint(out) ? Field::kRead : Field::kError;
}

// uint32, int32 and enum fields keep the varint's low 32 bits.
template <class T>
Field ReadVarint32(uint32_t wire, WireReader& r, T& out) {
  uint64_t v = 0;
  const Field f = ReadU64(wire, r, v);
  if (f == Field::kRead) out = static_cast<T>(static_cast<int32_t>(static_cast<uint32_t>(v)));
  return f;
}

Field ReadBool(uint32_t wire, WireReader& r, bool& out) {
  uint64_t v = 0;
  const Field f = ReadU64(wire, r, v);
  if (f == Field::kRead) out = v != 0;
  return f;
}

Field ReadDouble(uint32_t wire, WireReader& r, double& out) {
  if (wire != kFixed64) return Field::kUnknown;
  uint64_t bits = 0;
  if (!r.Fixed64(bits)) return Field::kError;
  std::memcpy(&out, &bits, sizeof out);
  return Field::kRead;
}

Field ReadFixed32(uint32_t wire, WireReader& r, uint32_t& out) {
  if (wire != kFixed32) return Field::kUnknown;
  return r.Fixed32(out) ? Field::kRead : Field::kError;
}

Field ReadBytes(uint32_t wire, WireReader& r, std::string& out) {
  if (wire != kLengthDelimited) return Field::kUnknown;
  std::string_view bytes;
  if (!r.Delimited(bytes)) return Field::kError;
  out.assign(bytes);
  return Field::kRead;
}

// Repeated double or float: one value per record, or a packed run whose
// length must be a multiple of the value's size.
template <class T>
Field ReadRepeatedFixed(uint32_t wire, WireReader& r, std::vector<T>& out) {
  static_assert(sizeof(T) == 8 || sizeof(T) == 4);
  using Bits = std::conditional_t<sizeof(T) == 8, uint64_t, uint32_t>;
  constexpr uint32_t kOne = sizeof(T) == 8 ? kFixed64 : kFixed32;
  T value;
  if (wire == kOne) {
    Bits bits = 0;
    if (!r.Fixed(bits)) return Field::kError;
    std::memcpy(&value, &bits, sizeof value);
    out.push_back(value);
    return Field::kRead;
  }
  if (wire != kLengthDelimited) return Field::kUnknown;
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
Field ReadRepeatedU32(uint32_t wire, WireReader& r, std::vector<uint32_t>& out) {
  uint64_t v = 0;
  if (wire == kVarint) {
    if (!r.Varint(v)) return Field::kError;
    out.push_back(static_cast<uint32_t>(v));
    return Field::kRead;
  }
  if (wire != kLengthDelimited) return Field::kUnknown;
  std::string_view packed;
  if (!r.Delimited(packed)) return Field::kError;
  WireReader values(packed);
  while (!values.done()) {
    if (!values.Varint(v)) return Field::kError;
    out.push_back(static_cast<uint32_t>(v));
  }
  return Field::kRead;
}

Field ReadSawt(uint32_t number, uint32_t wire, WireReader& r, StreamHeader::SawtChoices& s) {
  switch (number) {
    case 1: return ReadVarint32(wire, r, s.alpha);
    case 2: return ReadVarint32(wire, r, s.region_count);
    case 3: return ReadBytes(wire, r, s.coded);
    case 4: return ReadFixed32(wire, r, s.crc32c);
    default: return Field::kUnknown;
  }
}

Field ReadTransform(uint32_t number, uint32_t wire, WireReader& r, int depth,
                    StreamHeader::Transform& t) {
  switch (number) {
    case 1: return ReadVarint32(wire, r, t.predictor);
    case 2: return ReadVarint32(wire, r, t.update);
    case 3: return ReadBool(wire, r, t.local_frames);
    case 4: return ReadVarint32(wire, r, t.levels);
    case 5:
      if (wire != kLengthDelimited) return Field::kUnknown;
      // A repeated embedded message merges into the one already read.
      if (!t.sawt) t.sawt = StreamHeader::SawtChoices();
      return ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, WireReader& f, int) {
        return ReadSawt(n, w, f, *t.sawt);
      });
    default: return Field::kUnknown;
  }
}

Field ReadBase(uint32_t number, uint32_t wire, WireReader& r, StreamHeader::BaseMesh& b) {
  switch (number) {
    case 1: return ReadVarint32(wire, r, b.vertex_count);
    case 2: return ReadVarint32(wire, r, b.face_count);
    case 3: return ReadRepeatedFixed<double>(wire, r, b.origin);
    case 4: return ReadDouble(wire, r, b.step);
    case 6: return ReadBytes(wire, r, b.coded);
    case 7: return ReadVarint32(wire, r, b.refinement_planes);
    default: return Field::kUnknown;
  }
}

Field ReadQuantizer(uint32_t number, uint32_t wire, WireReader& r, StreamHeader::Quantizer& q) {
  switch (number) {
    case 1: return ReadDouble(wire, r, q.step);
    case 2: return ReadVarint32(wire, r, q.deadzone);
    case 3: return ReadVarint32(wire, r, q.top_bitplane);
    default: return Field::kUnknown;
  }
}

Field ReadIndex(uint32_t number, uint32_t wire, WireReader& r, StreamHeader::PacketIndex& p) {
  switch (number) {
    case 3: return ReadRepeatedU32(wire, r, p.length);
    case 6: return ReadBytes(wire, r, p.check);
    case 7: return ReadRepeatedFixed<float>(wire, r, p.chain_distortion);
    case 8: return ReadBytes(wire, r, p.distortion_step);
    case 9: return ReadVarint32(wire, r, p.precinct_coefficients);
    case 10: return ReadRepeatedU32(wire, r, p.split_planes);
    default: return Field::kUnknown;
  }
}

Field ReadHeaderField(uint32_t number, uint32_t wire, WireReader& r, int depth,
                      StreamHeader& h) {
  switch (number) {
    case 1: return ReadVarint32(wire, r, h.format_version);
    case 2: {
      const Field f = ReadBytes(wire, r, h.name);
      // proto3 strings must be UTF-8: protobuf refuses the message otherwise.
      if (f == Field::kRead && !IsValidUtf8(h.name)) return Field::kError;
      return f;
    }
    case 3: return ReadU64(wire, r, h.vertices);
    case 4: return ReadU64(wire, r, h.faces);
    case 5: return ReadRepeatedFixed<double>(wire, r, h.bbox_min);
    case 6: return ReadRepeatedFixed<double>(wire, r, h.bbox_max);
    case 7:
      if (wire != kLengthDelimited) return Field::kUnknown;
      return ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, WireReader& f, int d) {
        return ReadTransform(n, w, f, d, h.transform);
      });
    case 8: return ReadVarint32(wire, r, h.coder);
    case 9: return ReadVarint32(wire, r, h.octree_leaf_size);
    case 10:
      if (wire != kLengthDelimited) return Field::kUnknown;
      return ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, WireReader& f, int) {
        return ReadBase(n, w, f, h.base);
      });
    case 11:
      if (wire != kLengthDelimited) return Field::kUnknown;
      h.quantizers.emplace_back();
      return ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, WireReader& f, int) {
        return ReadQuantizer(n, w, f, h.quantizers.back());
      });
    case 12:
      if (wire != kLengthDelimited) return Field::kUnknown;
      return ReadEmbedded(r, depth, [&](uint32_t n, uint32_t w, WireReader& f, int) {
        return ReadIndex(n, w, f, h.packets);
      });
    case 13: return ReadDouble(wire, r, h.base_distortion);
    case kHeaderPresentField: return ReadRepeatedU32(wire, r, h.present);
    default: return Field::kUnknown;
  }
}

}  // namespace

Result<StreamHeader> ReadStreamHeader(std::string_view bytes) {
  StreamHeader h;
  const bool ok = ReadMessage(
      bytes, kMaxDepth,
      [&](uint32_t number, uint32_t wire, WireReader& r, int depth) {
        return ReadHeaderField(number, wire, r, depth, h);
      },
      [&](uint32_t tag, const char* begin, const char* end, bool known) {
        if (!(known && (tag >> 3) == kHeaderPresentField)) h.bytes_without_present.append(begin, end);
      });
  if (!ok) return ParseError("the stream header does not parse (malformed protobuf bytes)");
  return h;
}

}  // namespace meshwave
