// The query of GET /v1/meshes/{id}/stream: order, budget, max_level, from,
// and for region requests (docs/API.md) region or view, screen_error, held.
#ifndef MESHWAVE_SERVER_STREAM_QUERY_H_
#define MESHWAVE_SERVER_STREAM_QUERY_H_

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/status.h"
#include "request_target.h"

namespace meshwave::server {

// Budgets above this are refused: nothing we serve comes near, and it keeps
// every sum below 2^64.
inline constexpr uint64_t kMaxBudget = uint64_t{1} << 50;
inline constexpr int kMaxLevelLimit = 64;

struct StreamQuery {
  Progression order = Progression::kQuality;
  uint64_t budget = kMaxBudget;  // bytes; absent: everything
  int max_level = -1;            // -1: all levels
  uint64_t from = 0;             // cursor into the order
  std::optional<Region> region;  // region= or view= (with screen_error=)
  std::optional<std::string> held;  // the held bitmap's text, unchecked
  // A region request: units selected from what the client holds.
  bool units() const { return region.has_value() || held.has_value(); }
};

// kInvalidArgument for unknown parameters or orders, and for numbers that
// are not plain decimal integers in range (budget <= kMaxBudget, max_level
// <= kMaxLevelLimit, from < 2^32); for a region or view that does not parse
// (meshwave/region.h), both at once, screen_error without a view, and
// `from` in a region request. Limits that depend on the mesh (levels, order
// length, the held bitmap) are the handler's to check.
Result<StreamQuery> ParseStreamQuery(const QueryParams& query);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_STREAM_QUERY_H_
