#include "meshwave/client_message.h"

#include "meshwave/mesh_id.h"
#include "websocket.pb.h"

namespace meshwave {
namespace {

Status CheckRate(uint64_t rate) {
  if (rate > kMaxRate) return InvalidArgument("rate is above 2^40 bytes per second");
  if (rate != 0 && rate < kMinRate) {
    return InvalidArgument("rate " + std::to_string(rate) + " is below the minimum of " +
                           std::to_string(kMinRate) + " bytes per second (0: unpaced)");
  }
  return Status::Ok();
}

// The region fields a start, refine and resume share (same names in the
// three messages); proto3 leaves an empty string for "absent".
template <typename Message>
void RegionFields(const Message& m, StreamRequestFields& f) {
  if (!m.order().empty()) f.order = m.order();
  if (!m.region().empty()) f.region = m.region();
  if (!m.view().empty()) f.view = m.view();
  if (m.has_screen_error()) f.screen_error = m.screen_error();
}

// The fields a start and a resume share: mesh, order, level limit, budget,
// rate and the region fields.
template <typename Message>
Status StreamFields(const Message& m, ClientRequest& r, StreamRequestFields& f) {
  if (!IsValidMeshId(m.mesh_id())) {
    return InvalidArgument("invalid mesh id (12 lowercase hex digits)");
  }
  r.mesh_id = m.mesh_id();
  if (m.has_max_level()) f.max_level = m.max_level();
  if (m.has_budget()) f.budget = m.budget();
  MW_RETURN_IF_ERROR(CheckRate(m.rate()));
  r.rate = m.rate();
  RegionFields(m, f);
  return Status::Ok();
}

}  // namespace

Result<ClientRequest> ParseClientMessage(std::string_view bytes, const WsLimits& limits) {
  if (bytes.size() > limits.max_message_bytes) {
    return InvalidArgument("message of " + std::to_string(bytes.size()) +
                           " bytes, the limit is " + std::to_string(limits.max_message_bytes));
  }
  proto::ClientMessage m;
  if (!m.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    return InvalidArgument("the message is not a ClientMessage (proto/websocket.proto)");
  }
  ClientRequest r;
  StreamRequestFields f;
  switch (m.message_case()) {
    case proto::ClientMessage::kStart: {
      const auto& s = m.start();
      r.kind = ClientRequest::Kind::kStart;
      MW_RETURN_IF_ERROR(StreamFields(s, r, f));
      r.header_only = s.header_only();
      if (r.header_only && f.budget) return InvalidArgument("header_only takes no budget");
      break;
    }
    case proto::ClientMessage::kRefine: {
      const auto& s = m.refine();
      r.kind = ClientRequest::Kind::kRefine;
      r.extra_bytes = s.extra_bytes();
      if (r.extra_bytes == 0) return InvalidArgument("refine needs extra_bytes of at least 1");
      if (r.extra_bytes > kMaxBudget) return InvalidArgument("extra_bytes is above 2^50 bytes");
      RegionFields(s, f);
      r.refine_order = f.order.has_value();
      break;
    }
    case proto::ClientMessage::kResume: {
      const auto& s = m.resume();
      r.kind = ClientRequest::Kind::kResume;
      MW_RETURN_IF_ERROR(StreamFields(s, r, f));
      if (s.cursor() != 0) f.from = s.cursor();
      // A session counting units resumes with held; with a region or view
      // and no held, nothing is held (proto3 cannot tell an empty held from
      // none: an empty one without a region is a resume of packets).
      if (!s.held().empty()) f.held = s.held();
      break;
    }
    case proto::ClientMessage::MESSAGE_NOT_SET:
      return InvalidArgument("the message holds no request (start, refine or resume)");
  }
  MW_ASSIGN_OR_RETURN(r.stream, CheckStreamRequest(f));
  return r;
}

}  // namespace meshwave
