// The packets a stream request gets from a served mesh: the checks that
// depend on the mesh (level limit, cursor, a budget below the header) and
// the selection itself (SelectPackets, SelectPayloads). GET /stream and the
// WebSocket sessions share it, so both send the same packets for the same
// request.
#ifndef MESHWAVE_SERVER_STREAM_PLAN_H_
#define MESHWAVE_SERVER_STREAM_PLAN_H_

#include <cstdint>
#include <vector>

#include "meshwave/progression.h"
#include "meshwave/status.h"
#include "served_mesh.h"

namespace meshwave::server {

struct StreamPlan {
  const std::vector<uint32_t>* order = nullptr;  // owned by the mesh
  Selection selection;
  bool complete() const { return selection.next_cursor == order->size(); }
};

// With `with_header` the bytes sent start with the header (GET /stream from
// cursor 0, a WebSocket StreamRequest) and the budget counts the whole
// container; without, it counts the payloads from `from` (any cursor, 0
// included). kInvalidArgument, with a message for the client, for a level
// limit above the mesh's levels, a cursor past the end of the order and a
// budget smaller than the header.
Result<StreamPlan> PlanStream(const ServedMesh& mesh, Progression order,
                              int max_level, uint64_t from, uint64_t budget,
                              bool with_header);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_STREAM_PLAN_H_
