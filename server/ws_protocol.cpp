#include "ws_protocol.h"

#include "core/protobuf_wire.h"
#include "mesh_id.h"
#include "stream_query.h"
#include "meshwave/region_text.h"

namespace meshwave::server {
namespace {

Status Bad(const std::string& what) { return InvalidArgument(what); }

Result<Progression> ParseOrder(const std::string& name) {
  if (name.empty()) return Progression::kQuality;
  auto p = ParseProgression(name);
  if (!p.ok()) {
    // The name comes from the client: quote a bounded, printable part.
    std::string shown = name.substr(0, 32);
    for (char& c : shown) {
      if (static_cast<unsigned char>(c) < 0x20 ||
          static_cast<unsigned char>(c) > 0x7e)
        c = '?';
    }
    return Bad("unknown order '" + shown + "' (quality, resolution, rd)");
  }
  return *p;
}

Status CheckMeshId(const std::string& id) {
  if (!IsValidMeshId(id))
    return Bad("invalid mesh id (12 lowercase hex digits)");
  return Status::Ok();
}

Result<int> ParseMaxLevel(bool has, uint32_t level) {
  if (!has) return -1;
  if (level > static_cast<uint32_t>(kMaxLevelLimit)) {
    return Bad("max_level " + std::to_string(level) + " is above " +
               std::to_string(kMaxLevelLimit));
  }
  return static_cast<int>(level);
}

Result<std::optional<uint64_t>> ParseBudget(bool has, uint64_t budget) {
  if (!has) return std::optional<uint64_t>();
  if (budget > kMaxBudget) return Bad("budget is above 2^50 bytes");
  return std::optional<uint64_t>(budget);
}

Status CheckRate(uint64_t rate) {
  if (rate > kMaxRate) return Bad("rate is above 2^40 bytes per second");
  if (rate != 0 && rate < kMinRate) {
    return Bad("rate " + std::to_string(rate) + " is below the minimum of " +
               std::to_string(kMinRate) + " bytes per second (0: unpaced)");
  }
  return Status::Ok();
}

// The fields a start and a resume share (same names in both messages):
// mesh, order, level limit, budget and rate, each checked.
template <typename StreamFields>
Status ParseStreamFields(const StreamFields& s, ClientRequest& r) {
  MW_RETURN_IF_ERROR(CheckMeshId(s.mesh_id()));
  r.mesh_id = s.mesh_id();
  MW_ASSIGN_OR_RETURN(r.order, ParseOrder(s.order()));
  MW_ASSIGN_OR_RETURN(r.max_level, ParseMaxLevel(s.has_max_level(), s.max_level()));
  MW_ASSIGN_OR_RETURN(r.budget, ParseBudget(s.has_budget(), s.budget()));
  MW_RETURN_IF_ERROR(CheckRate(s.rate()));
  r.rate = s.rate();
  return Status::Ok();
}

// A region or view and its screen error, as the three fields of a start,
// refine or resume carry them (ASCII text forms of meshwave/region.h).
Result<std::optional<Region>> ParseRegionFields(const std::string& region, const std::string& view,
                                                bool has_screen_error, double screen_error) {
  if (!region.empty() && !view.empty()) return Bad("region and view: ask for one of them");
  if (has_screen_error && view.empty()) return Bad("screen_error applies to a view only");
  if (region.empty() && view.empty()) return std::optional<Region>();
  auto r = region.empty() ? ParseViewRegion(view) : ParseSphereRegion(region);
  if (!r.ok()) return Bad((region.empty() ? "view: " : "region: ") + r.status().message());
  if (has_screen_error) {
    auto px = CheckScreenError(screen_error);
    if (!px.ok()) return Bad("screen_error: " + px.status().message());
    r->screen_error_px = *px;
  }
  return std::optional<Region>(*std::move(r));
}

}  // namespace

Result<ClientRequest> ParseClientMessage(std::string_view bytes,
                                         const WsLimits& limits) {
  if (bytes.size() > limits.max_message_bytes) {
    return Bad("message of " + std::to_string(bytes.size()) +
               " bytes, the limit is " +
               std::to_string(limits.max_message_bytes));
  }
  proto::ClientMessage m;
  if (!m.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return Bad("the message is not a ClientMessage (proto/websocket.proto)");
  }
  ClientRequest r;
  switch (m.message_case()) {
    case proto::ClientMessage::kStart: {
      const auto& s = m.start();
      r.kind = ClientRequest::Kind::kStart;
      MW_RETURN_IF_ERROR(ParseStreamFields(s, r));
      r.header_only = s.header_only();
      if (r.header_only && r.budget) return Bad("header_only takes no budget");
      MW_ASSIGN_OR_RETURN(r.region, ParseRegionFields(s.region(), s.view(), s.has_screen_error(),
                                                      s.screen_error()));
      if (r.region && !s.order().empty()) return Bad("order and a region: ask for one of them");
      return r;
    }
    case proto::ClientMessage::kRefine: {
      r.kind = ClientRequest::Kind::kRefine;
      r.extra_bytes = m.refine().extra_bytes();
      if (r.extra_bytes == 0)
        return Bad("refine needs extra_bytes of at least 1");
      if (r.extra_bytes > kMaxBudget)
        return Bad("extra_bytes is above 2^50 bytes");
      const auto& f = m.refine();
      MW_ASSIGN_OR_RETURN(r.region, ParseRegionFields(f.region(), f.view(), f.has_screen_error(),
                                                      f.screen_error()));
      if (!f.order().empty()) {
        if (r.region) return Bad("order and a region: ask for one of them");
        MW_ASSIGN_OR_RETURN(r.order, ParseOrder(f.order()));
        r.refine_order = true;
      }
      return r;
    }
    case proto::ClientMessage::kResume: {
      const auto& s = m.resume();
      r.kind = ClientRequest::Kind::kResume;
      MW_RETURN_IF_ERROR(ParseStreamFields(s, r));
      r.cursor = s.cursor();
      MW_ASSIGN_OR_RETURN(r.region, ParseRegionFields(s.region(), s.view(), s.has_screen_error(),
                                                      s.screen_error()));
      if (r.region && !s.order().empty()) return Bad("order and a region: ask for one of them");
      if (!s.held().empty() || r.region) {
        if (r.cursor != 0) return Bad("cursor and held: a session counting units resumes with held");
        r.held = s.held();
      }
      return r;
    }
    case proto::ClientMessage::MESSAGE_NOT_SET:
      break;
  }
  return Bad("the message holds no request (start, refine or resume)");
}

std::string ErrorMessage(proto::Error::Code code, std::string_view message) {
  proto::ServerMessage m;
  m.mutable_error()->set_code(code);
  m.mutable_error()->set_message(std::string(message));
  return m.SerializeAsString();
}

std::string PacketMessagePrefix(uint32_t cursor, uint32_t id,
                                uint64_t payload_size, std::optional<uint32_t> part) {
  // Wire format, fields in number order as protobuf writes them but `part`
  // (4) before the payload (3), which must come last; proto3 leaves zero
  // numbers and empty bytes out, an optional field is written when set.
  // Every tag is one byte (field numbers below 16).
  constexpr uint32_t kPacketTag =
      WireTag(proto::ServerMessage::kPacketFieldNumber, kLengthDelimited);
  constexpr uint32_t kCursorTag = WireTag(proto::Packet::kCursorFieldNumber, kVarint);
  constexpr uint32_t kIdTag = WireTag(proto::Packet::kIdFieldNumber, kVarint);
  constexpr uint32_t kPayloadTag = WireTag(proto::Packet::kPayloadFieldNumber, kLengthDelimited);
  constexpr uint32_t kPartTag = WireTag(proto::Packet::kPartFieldNumber, kVarint);
  static_assert(kPacketTag < 0x80 && kCursorTag < 0x80 && kIdTag < 0x80 && kPayloadTag < 0x80 &&
                kPartTag < 0x80);
  uint64_t inner = 0;
  if (cursor != 0) inner += 1 + VarintSize(cursor);
  if (id != 0) inner += 1 + VarintSize(id);
  if (part) inner += 1 + VarintSize(*part);
  if (payload_size != 0) inner += 1 + VarintSize(payload_size) + payload_size;
  std::string out;
  out.reserve(24);
  PutVarint(out, kPacketTag);
  PutVarint(out, inner);
  if (cursor != 0) {
    PutVarint(out, kCursorTag);
    PutVarint(out, cursor);
  }
  if (id != 0) {
    PutVarint(out, kIdTag);
    PutVarint(out, id);
  }
  if (part) {
    PutVarint(out, kPartTag);
    PutVarint(out, *part);
  }
  if (payload_size != 0) {
    PutVarint(out, kPayloadTag);
    PutVarint(out, payload_size);
  }
  return out;
}

}  // namespace meshwave::server
