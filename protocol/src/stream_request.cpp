#include "meshwave/stream_request.h"

#include <limits>
#include <utility>

#include "meshwave/region_text.h"

namespace meshwave {
namespace {

// A region or a view, and a view's screen error.
Result<std::optional<Region>> ParseRegionFields(const StreamRequestFields& f) {
  if (f.region && f.view) return InvalidArgument("region and view: ask for one of them");
  if (f.screen_error && !f.view) return InvalidArgument("screen_error applies to a view only");
  if (!f.region && !f.view) return std::optional<Region>();
  auto r = f.region ? ParseSphereRegion(*f.region) : ParseViewRegion(*f.view);
  if (!r.ok()) return InvalidArgument((f.region ? "region: " : "view: ") + r.status().message());
  if (f.screen_error) {
    auto px = CheckScreenError(*f.screen_error);
    if (!px.ok()) return InvalidArgument("screen_error: " + px.status().message());
    r->screen_error_px = *px;
  }
  return std::optional<Region>(*std::move(r));
}

// A number of the query: plain decimal digits, up to 2^64 - 1 (the ranges
// are CheckStreamRequest's).
Status QueryNumber(const QueryParams& query, std::string_view key,
                   std::optional<uint64_t>& out) {
  if (auto text = query.Get(key)) {
    MW_ASSIGN_OR_RETURN(out, ParseUnsigned(*text, std::numeric_limits<uint64_t>::max(), key));
  }
  return Status::Ok();
}

}  // namespace

Result<StreamRequest> CheckStreamRequest(const StreamRequestFields& f) {
  StreamRequest r;
  if (f.order) {
    MW_ASSIGN_OR_RETURN(r.order, ParseProgression(std::string(*f.order)));
  }
  if (f.budget) {
    if (*f.budget > kMaxBudget) return InvalidArgument("budget is above 2^50 bytes");
    r.budget = *f.budget;
  }
  if (f.max_level) {
    if (*f.max_level > static_cast<uint64_t>(kMaxLevelLimit)) {
      return InvalidArgument("max_level " + std::to_string(*f.max_level) + " is above " +
                             std::to_string(kMaxLevelLimit));
    }
    r.max_level = static_cast<int>(*f.max_level);
  }
  if (f.from) {
    if (*f.from > 0xffffffffu) return InvalidArgument("from is at or above 2^32");
    r.from = *f.from;
  }
  MW_ASSIGN_OR_RETURN(r.region, ParseRegionFields(f));
  if (r.region && f.order) return InvalidArgument("order and a region: ask for one of them");
  if (f.held) r.held = std::string(*f.held);
  if (r.units() && f.from) {
    return InvalidArgument(
        "from does not apply to a request for units (region, view or held): name the units "
        "held with held");
  }
  return r;
}

Result<StreamRequest> ParseStreamQuery(const QueryParams& query) {
  MW_RETURN_IF_ERROR(query.CheckAllowed(
      {"order", "budget", "max_level", "from", "region", "view", "screen_error", "held"}));
  StreamRequestFields f;
  const auto order = query.Get("order");
  const auto region = query.Get("region");
  const auto view = query.Get("view");
  const auto held = query.Get("held");
  if (order) f.order = *order;
  if (region) f.region = *region;
  if (view) f.view = *view;
  if (held) f.held = *held;
  MW_RETURN_IF_ERROR(QueryNumber(query, "budget", f.budget));
  MW_RETURN_IF_ERROR(QueryNumber(query, "max_level", f.max_level));
  MW_RETURN_IF_ERROR(QueryNumber(query, "from", f.from));
  if (auto px = query.Get("screen_error")) {
    auto n = ParseScreenError(*px);
    if (!n.ok()) return InvalidArgument("screen_error: " + n.status().message());
    f.screen_error = *n;
  }
  return CheckStreamRequest(f);
}

}  // namespace meshwave
