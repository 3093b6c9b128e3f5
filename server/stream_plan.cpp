#include "stream_plan.h"

#include <string>

#include "meshwave/container.h"

namespace meshwave::server {

Result<StreamPlan> PlanStream(const ServedMesh& mesh, Progression order,
                              int max_level, uint64_t from, uint64_t budget,
                              bool with_header) {
  MW_RETURN_IF_ERROR(mesh.CheckLevelLimit(max_level));
  StreamPlan plan;
  plan.order = &mesh.Order(order, max_level);
  if (from > plan.order->size()) {
    return InvalidArgument("from " + std::to_string(from) +
                           " is past the end of the order (" +
                           std::to_string(plan.order->size()) + " packets)");
  }
  if (with_header) {
    plan.selection = SelectPackets(mesh.header(), *plan.order, budget, 0);
    if (plan.selection.bytes == 0) {
      return InvalidArgument("budget " + std::to_string(budget) +
                             " is smaller than the stream header (" +
                             std::to_string(ContainerSize(mesh.header(), {})) +
                             " bytes)");
    }
  } else {
    plan.selection = SelectPayloads(mesh.header(), *plan.order, budget, from);
  }
  return plan;
}

}  // namespace meshwave::server
