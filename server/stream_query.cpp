#include "stream_query.h"

namespace meshwave::server {

Result<StreamQuery> ParseStreamQuery(const QueryParams& query) {
  MW_RETURN_IF_ERROR(query.CheckAllowed({"order", "budget", "max_level", "from"}));
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
  return q;
}

}  // namespace meshwave::server
