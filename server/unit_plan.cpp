#include "unit_plan.h"

#include <string>

#include "meshwave/screen_errors.h"

namespace meshwave::server {
namespace {

std::vector<StreamUnit> UniformUnits(const ServedMesh& mesh, const HeldUnits& held,
                                     Progression order, int max_level) {
  std::vector<StreamUnit> out;
  for (uint32_t id : mesh.Order(order, max_level)) {
    if (held.Has({id})) continue;
    const uint32_t parts = held.PartCount(id);
    bool any_part = false;
    for (uint32_t p = 0; p < parts && !any_part; ++p) any_part = held.Has({id, p});
    if (!any_part) {
      out.push_back({id});
      continue;
    }
    for (uint32_t p = 0; p < parts; ++p) {
      if (!held.Has({id, p})) out.push_back({id, p});
    }
  }
  return out;
}

}  // namespace

Result<UnitPlan> PlanUnits(const ServedMesh& mesh, const UnitTable& table, const HeldUnits& held,
                           const UnitRequest& request) {
  MW_RETURN_IF_ERROR(mesh.CheckLevelLimit(request.max_level));
  // A screen-space error is judged by the stream's measured errors; a
  // stream they cannot be measured on (it would not decode either) by the
  // quantisers' bound.
  const StreamScreenErrors* measured = nullptr;
  if (request.region && request.region->screen_error_px) {
    if (auto m = mesh.screen_errors(); m.ok()) measured = *m;
  }
  const std::vector<StreamUnit> lacking =
      request.region ? RegionOrder(mesh.header(), table.precincts(), table.part_lengths(),
                                   *request.region, held, request.max_level, measured)
                     : UniformUnits(mesh, held, request.order, request.max_level);
  UnitPlan plan;
  for (const StreamUnit& u : lacking) {
    const uint64_t length = table.Length(mesh.payload(u.id).size(), u);
    if (length > request.budget - plan.bytes) break;
    plan.bytes += length;
    plan.units.push_back(u);
  }
  plan.complete = plan.units.size() == lacking.size();
  return plan;
}

}  // namespace meshwave::server
