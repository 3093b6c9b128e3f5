#include "meshwave/stream_units.h"

#include <optional>

#include "core/base64.h"
#include "core/protobuf_wire.h"

namespace meshwave {
namespace {

// A varint of at most 32 bits from the start of `in`: its value and
// length, 0 length when `in` ends first, nullopt when it is malformed.
struct Varint {
  uint32_t value = 0;
  size_t length = 0;
};

std::optional<Varint> ReadVarint32(std::string_view in) {
  uint64_t v = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i == 5) return std::nullopt;
    const auto byte = static_cast<uint8_t>(in[i]);
    v |= uint64_t{byte & 0x7fu} << (7 * i);
    if (!(byte & 0x80)) {
      if (v > 0xffffffffu) return std::nullopt;
      return Varint{static_cast<uint32_t>(v), i + 1};
    }
  }
  if (in.size() >= 5) return std::nullopt;
  return Varint{};
}

std::string Describe(StreamUnit u) {
  return u.whole() ? "packet " + std::to_string(u.id)
                   : "part " + std::to_string(u.part) + " of packet " + std::to_string(u.id);
}

}  // namespace

UnitNumbering::UnitNumbering(const HeldUnits& units) {
  first_.reserve(units.packet_count());
  for (uint32_t id = 0; id < units.packet_count(); ++id) {
    first_.push_back(units_.size());
    const uint32_t parts = units.PartCount(id);
    if (parts == 0) units_.push_back({id});
    for (uint32_t p = 0; p < parts; ++p) units_.push_back({id, p});
  }
}

std::string EncodeHeldUnits(const HeldUnits& held, const UnitNumbering& numbering) {
  std::string bitmap;
  for (size_t n = 0; n < numbering.size(); ++n) {
    if (!held.Has(numbering.unit(n))) continue;
    if (bitmap.size() <= n / 8) bitmap.resize(n / 8 + 1, '\0');
    bitmap[n / 8] = static_cast<char>(static_cast<uint8_t>(bitmap[n / 8]) | 1u << (n % 8));
  }
  return Base64Url(bitmap);
}

Status DecodeHeldUnits(std::string_view text, const UnitNumbering& numbering, HeldUnits& held) {
  const std::optional<std::string> bitmap = DecodeBase64Url(text);
  if (!bitmap) return InvalidArgument("held units: not base64url (A-Z a-z 0-9 - _, no padding)");
  if (bitmap->size() > (numbering.size() + 7) / 8) {
    return InvalidArgument("held units: " + std::to_string(bitmap->size()) +
                           " bytes of bitmap for a stream of " +
                           std::to_string(numbering.size()) + " units");
  }
  // Numbers follow the packet ids, and every unit needs only units of
  // lower ids: one pass in number order sees what each needs first.
  for (size_t n = 0; n < bitmap->size() * 8; ++n) {
    if (!(static_cast<uint8_t>((*bitmap)[n / 8]) >> (n % 8) & 1)) continue;
    if (n >= numbering.size()) {
      return InvalidArgument("held units: bit " + std::to_string(n) + " set, the stream has " +
                             std::to_string(numbering.size()) + " units");
    }
    const StreamUnit u = numbering.unit(n);
    if (!held.Ready(u)) {
      return InvalidArgument("held units: " + Describe(u) + " (unit " + std::to_string(n) +
                             ") is held without a unit it depends on");
    }
    held.Add(u);
  }
  return Status::Ok();
}

void AppendUnitRecord(std::string& out, StreamUnit unit, std::string_view payload) {
  PutVarint(out, unit.id);
  PutVarint(out, unit.whole() ? 0 : uint64_t{unit.part} + 1);
  PutVarint(out, payload.size());
  out.append(payload);
}

Status UnitRecordReader::Feed(std::string_view bytes) {
  // Parse straight from `bytes` when nothing is buffered; otherwise append
  // and parse the buffer.
  std::string_view in = bytes;
  if (!buffer_.empty()) {
    buffer_.append(bytes);
    in = buffer_;
  }
  size_t used = 0;
  while (used < in.size()) {
    std::string_view rest = in.substr(used);
    uint32_t fields[3];
    size_t at = 0;
    bool whole_head = true;
    for (uint32_t& f : fields) {
      const auto v = ReadVarint32(rest.substr(at));
      if (!v) return ParseError("unit record " + std::to_string(records_) + ": malformed varint");
      if (v->length == 0) {
        whole_head = false;
        break;
      }
      f = v->value;
      at += v->length;
    }
    if (!whole_head) break;
    if (fields[2] > max_payload_) {
      return ParseError("unit record " + std::to_string(records_) + ": payload of " +
                        std::to_string(fields[2]) + " bytes, longer than any of the stream's (" +
                        std::to_string(max_payload_) + ")");
    }
    if (rest.size() - at < fields[2]) break;
    const StreamUnit unit{fields[0], fields[1] == 0 ? StreamUnit::kWholePacket : fields[1] - 1};
    MW_RETURN_IF_ERROR(on_unit_(unit, rest.substr(at, fields[2])));
    ++records_;
    used += at + fields[2];
  }
  if (in.data() == buffer_.data() && !buffer_.empty()) {
    buffer_.erase(0, used);
  } else {
    buffer_.assign(in.substr(used));
  }
  return Status::Ok();
}

}  // namespace meshwave
