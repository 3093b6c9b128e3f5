// One client's place in one mesh's stream (docs/API.md): what its requests
// selected and what is still to be sent, counting packets of an order or,
// once a request names a region, a view or held units, units (whole
// packets and parts of split packets). No socket and no clock: WsSession
// drives one per connection, paced and framed; GET /stream drives one per
// request and sends everything it selects. Both therefore select the same
// units for the same request.
#ifndef MESHWAVE_SERVER_STREAM_CURSOR_H_
#define MESHWAVE_SERVER_STREAM_CURSOR_H_

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "meshwave/held_units.h"
#include "meshwave/status.h"
#include "meshwave/stream_request.h"
#include "served_mesh.h"
#include "unit_plan.h"

namespace meshwave::server {

class StreamCursor {
 public:
  // What one request selected: cursors [from, next) of the order (packets)
  // or of the units selected so far, and their bytes.
  struct Selection {
    size_t from = 0;
    size_t next = 0;
    size_t order_length = 0;  // packets of the order, or units below the level limit
    // Payload bytes of the selection, plus the header's container bytes
    // when the request counted them (a start; GET /stream from cursor 0).
    uint64_t bytes = 0;
    bool complete = false;    // nothing the order could send is left after it
  };
  // The unit at the cursor, its payload a view into the mesh's memory map.
  struct Unit {
    size_t cursor = 0;
    StreamUnit unit;
    std::string_view payload;
  };
  // What a request is owed once every unit it selected is sent.
  struct Done {
    size_t next = 0;
    bool complete = false;
  };

  // Starts over on `mesh`: a start (`with_header`: the budget counts the
  // header's container, as a container's does; `header_only`: exactly the
  // header) or a resume from request.from (payloads only). A request for
  // units (StreamRequest::units()) continues from its held bitmap.
  // kInvalidArgument with a message for the client (a level limit above the
  // mesh's levels, a cursor past the order's end, a budget below the
  // header, a held bitmap that is not this mesh's); the mesh's own errors
  // when its units cannot be built. On error the cursor is unchanged.
  Result<Selection> Start(std::shared_ptr<const ServedMesh> mesh, const StreamRequest& request,
                          bool with_header, bool header_only = false);
  // `extra_bytes` more of payloads after what is selected. A region or an
  // order (a new one) switches a cursor counting packets to units, the
  // packets selected so far held, and refines in that order from then on.
  // Errors as Start's (kInvalidArgument before any Start).
  Result<Selection> Refine(uint64_t extra_bytes, const std::optional<Region>& region,
                           std::optional<Progression> order);

  bool started() const { return mesh_ != nullptr; }
  const ServedMesh* mesh() const { return mesh_.get(); }
  const std::shared_ptr<const ServedMesh>& shared_mesh() const { return mesh_; }
  // The unit to send next, if any is selected and not yet sent.
  std::optional<Unit> Peek() const;
  // The unit Peek gave is sent: moves past it.
  void Advance() { ++cursor_; }
  // The Done owed at the cursor, if a request's units are all sent (in
  // request order); TakeDone removes it.
  std::optional<Done> DoneDue() const;
  void TakeDone() { done_at_.pop_front(); }
  // Requests whose Done is still owed.
  size_t pending() const { return done_at_.size(); }

 private:
  // Selects what the held units lack in unit_request_'s order within
  // `budget` payload bytes and marks it held.
  UnitPlan SelectUnits(uint64_t budget);
  Selection UnitSelection(size_t from, const UnitPlan& plan, uint64_t bytes) const;
  // Switches a cursor counting packets of order_ to counting units.
  Status SwitchToUnits();

  std::shared_ptr<const ServedMesh> mesh_;
  // Counting packets: order_[cursor_ .. end_) is still to send; counting
  // units (order_ null): selected_[cursor_ .. end_).
  const std::vector<uint32_t>* order_ = nullptr;
  size_t cursor_ = 0;
  size_t end_ = 0;
  int max_level_ = -1;
  // Counting units: the mesh's unit table, everything selected so far (the
  // client holds it once sent), the order or region a refine continues,
  // and the units selected, one per cursor.
  const UnitTable* units_ = nullptr;
  std::optional<HeldUnits> held_;
  UnitRequest unit_request_;
  std::vector<StreamUnit> selected_;
  std::deque<Done> done_at_;
};

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_STREAM_CURSOR_H_
