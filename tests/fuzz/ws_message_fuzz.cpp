// Fuzz target: the WebSocket protocol's client-message parser
// (ParseClientMessage) on arbitrary frames, and the server-message framing
// (PacketMessagePrefix) with values taken from the input. A request that
// parses must respect every documented bound; a packet frame must parse
// back to the same cursor, id and payload.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "meshwave/client_message.h"
#include "meshwave/mesh_id.h"
#include "ws_protocol.h"

using namespace meshwave;
using namespace meshwave::server;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  WsLimits limits;
  limits.max_message_bytes = 4096;
  auto r = ParseClientMessage(bytes, limits);
  if (r.ok()) {
    fuzz::Require(size <= limits.max_message_bytes, "the size limit holds");
    const ClientRequest& q = *r;
    if (q.kind != ClientRequest::Kind::kRefine) {
      fuzz::Require(IsValidMeshId(q.mesh_id), "a request names a valid mesh id");
      fuzz::Require(q.stream.max_level >= -1 && q.stream.max_level <= kMaxLevelLimit,
                    "max_level in range");
      fuzz::Require(!q.stream.budget || *q.stream.budget <= kMaxBudget, "budget in range");
      fuzz::Require(q.rate <= kMaxRate, "rate in range");
      fuzz::Require(q.rate == 0 || q.rate >= kMinRate, "a paced rate is at least the minimum");
    } else {
      fuzz::Require(q.extra_bytes >= 1 && q.extra_bytes <= kMaxBudget, "extra_bytes in range");
    }
    if (q.header_only) fuzz::Require(!q.stream.budget, "header_only has no budget");
  } else {
    fuzz::Require(!r.status().message().empty(), "a refusal says why");
  }
  // Server framing: cursor and id from the first bytes, the rest as payload.
  if (size >= 8) {
    uint32_t cursor, id;
    std::memcpy(&cursor, data, 4);
    std::memcpy(&id, data + 4, 4);
    const std::string_view payload = bytes.substr(8);
    const std::string frame = PacketMessagePrefix(cursor, id, payload.size()) + std::string(payload);
    proto::ServerMessage m;
    fuzz::Require(m.ParseFromString(frame) && m.has_packet(), "a packet frame parses");
    fuzz::Require(m.packet().cursor() == cursor && m.packet().id() == id &&
                      m.packet().payload() == payload,
                  "a packet frame round-trips");
  }
  return 0;
}
