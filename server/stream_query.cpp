#include "stream_query.h"
#include "meshwave/region_text.h"

namespace meshwave::server {

Result<StreamQuery> ParseStreamQuery(const QueryParams& query) {
  MW_RETURN_IF_ERROR(query.CheckAllowed(
      {"order", "budget", "max_level", "from", "region", "view", "screen_error", "held"}));
  StreamQuery q;
  if (auto order = query.Get("order")) {
    auto p = ParseProgression(*order);
    if (!p.ok()) return InvalidArgument("unknown order '" + *order + "' (quality, resolution, rd)");
    q.order = *p;
  }
  if (auto budget = query.Get("budget")) {
    MW_ASSIGN_OR_RETURN(q.budget, ParseUnsigned(*budget, kMaxBudget, "budget"));
  }
  if (auto level = query.Get("max_level")) {
    MW_ASSIGN_OR_RETURN(uint64_t l, ParseUnsigned(*level, kMaxLevelLimit, "max_level"));
    q.max_level = static_cast<int>(l);
  }
  if (auto from = query.Get("from")) {
    MW_ASSIGN_OR_RETURN(q.from, ParseUnsigned(*from, 0xffffffffu, "from"));
  }
  const auto region = query.Get("region");
  const auto view = query.Get("view");
  const auto screen_error = query.Get("screen_error");
  if (region && view) return InvalidArgument("region and view: ask for one of them");
  if (screen_error && !view) return InvalidArgument("screen_error applies to a view only");
  if (region) {
    auto r = ParseSphereRegion(*region);
    if (!r.ok()) return InvalidArgument("region: " + r.status().message());
    q.region = *std::move(r);
  } else if (view) {
    auto r = ParseViewRegion(*view);
    if (!r.ok()) return InvalidArgument("view: " + r.status().message());
    q.region = *std::move(r);
    if (screen_error) {
      auto px = ParseScreenError(*screen_error);
      if (!px.ok()) return InvalidArgument("screen_error: " + px.status().message());
      q.region->screen_error_px = *px;
    }
  }
  if (auto held = query.Get("held")) q.held = *held;
  if (q.units() && query.Get("from")) {
    return InvalidArgument("from does not apply to a region request: name the units held with held=");
  }
  return q;
}

}  // namespace meshwave::server
