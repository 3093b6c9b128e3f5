// The units a region request gets (docs/API.md, "Region requests"): from
// what the client holds, the region order (meshwave/region_order.h) or a
// uniform order over the units it lacks, as many as fit the budget. GET
// /stream and the WebSocket sessions share it.
#ifndef MESHWAVE_SERVER_UNIT_PLAN_H_
#define MESHWAVE_SERVER_UNIT_PLAN_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/region_order.h"
#include "meshwave/status.h"
#include "served_mesh.h"

namespace meshwave::server {

struct UnitRequest {
  std::optional<Region> region;  // absent: the uniform `order`
  Progression order = Progression::kQuality;
  int max_level = -1;            // -1: all levels
  uint64_t budget = 0;           // payload bytes
};

struct UnitPlan {
  std::vector<StreamUnit> units;  // in the order to send them
  uint64_t bytes = 0;             // their payloads
  bool complete = false;          // nothing the order could send is left
};

// The longest run of the units `held` lacks, in the request's order, whose
// payloads fit the budget. A uniform order sends each packet it lists that
// is not held: whole, or the parts of it that are missing.
// kInvalidArgument for a level limit above the mesh's levels.
Result<UnitPlan> PlanUnits(const ServedMesh& mesh, const UnitTable& table, const HeldUnits& held,
                           const UnitRequest& request);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_UNIT_PLAN_H_
