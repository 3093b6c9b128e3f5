// What a client asks of one mesh's stream (docs/API.md): an order, or a
// region or view to refine first; a byte budget; a level limit; where to
// continue (a cursor into the order, or the units held). One type for both
// transports: GET /v1/meshes/{id}/stream's query (ParseStreamQuery) and the
// WebSocket's start and resume (ParseClientMessage,
// meshwave/client_message.h) gather their fields as they arrive and
// CheckStreamRequest checks them, once, with the same rules and messages.
#ifndef MESHWAVE_STREAM_REQUEST_H_
#define MESHWAVE_STREAM_REQUEST_H_

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/request_target.h"
#include "meshwave/status.h"

namespace meshwave {

// Budgets above this are refused: nothing we serve comes near, and it keeps
// every sum below 2^64.
inline constexpr uint64_t kMaxBudget = uint64_t{1} << 50;
inline constexpr int kMaxLevelLimit = 64;

struct StreamRequest {
  Progression order = Progression::kQuality;
  std::optional<uint64_t> budget;   // bytes, at most kMaxBudget; absent: everything
  int max_level = -1;               // -1: all levels
  uint64_t from = 0;                // cursor into the order (below 2^32)
  std::optional<Region> region;     // a sphere or a view (with its screen error)
  std::optional<std::string> held;  // the held bitmap's text, unchecked
  // A region request: units selected from what the client holds.
  bool units() const { return region.has_value() || held.has_value(); }
};

// A stream request's fields as they arrive, unchecked: absent when the
// query or the message does not give them.
struct StreamRequestFields {
  std::optional<std::string_view> order;  // a name
  std::optional<uint64_t> budget;
  std::optional<uint64_t> max_level;
  std::optional<uint64_t> from;
  std::optional<std::string_view> region;  // text forms (meshwave/region_text.h)
  std::optional<std::string_view> view;
  std::optional<double> screen_error;      // pixels
  std::optional<std::string_view> held;
};

// kInvalidArgument, with a message for the client, for an unknown order
// (quoted as meshwave's messages quote untrusted text), a budget above
// kMaxBudget, max_level above kMaxLevelLimit, from at or above 2^32; a
// region or view that does not parse, both at once, a screen error without
// a view, an order beside a region or view, and `from` in a request for
// units (one with a region, a view or held units). Limits that depend on
// the mesh (levels, order length, the held bitmap) are the server's to
// check.
Result<StreamRequest> CheckStreamRequest(const StreamRequestFields& fields);

// GET /v1/meshes/{id}/stream's query: order, budget, max_level, from,
// region, view, screen_error, held. kInvalidArgument for any other
// parameter, for numbers that are not plain decimal integers (ParseUnsigned)
// and for what CheckStreamRequest refuses.
Result<StreamRequest> ParseStreamQuery(const QueryParams& query);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_REQUEST_H_
