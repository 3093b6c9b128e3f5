#include "stream_cursor.h"

#include <string>
#include <utility>

#include "meshwave/container.h"
#include "meshwave/stream_units.h"
#include "stream_plan.h"

namespace meshwave::server {

Result<StreamCursor::Selection> StreamCursor::Start(std::shared_ptr<const ServedMesh> mesh,
                                                    const StreamRequest& r, bool with_header,
                                                    bool header_only) {
  // A start's budget counts the header, as a container's does.
  const uint64_t header = with_header ? ContainerSize(mesh->header(), {}) : 0;
  uint64_t budget = r.budget.value_or(kMaxBudget);
  // Exactly the header's container: no packet fits beside it.
  if (header_only) budget = header;
  if (!r.units()) {
    MW_ASSIGN_OR_RETURN(const StreamPlan plan,
                        PlanStream(*mesh, r.order, r.max_level, r.from, budget, with_header));
    mesh_ = std::move(mesh);
    order_ = plan.order;
    max_level_ = r.max_level;
    units_ = nullptr;
    held_.reset();
    selected_.clear();
    cursor_ = r.from;
    end_ = plan.selection.next_cursor;
    done_at_.push_back({end_, plan.complete()});
    return Selection{cursor_, end_, order_->size(), plan.selection.bytes, plan.complete()};
  }
  MW_RETURN_IF_ERROR(mesh->CheckLevelLimit(r.max_level));
  MW_ASSIGN_OR_RETURN(const UnitTable* table, mesh->units());
  HeldUnits held = table->nothing_held();
  if (r.held) MW_RETURN_IF_ERROR(DecodeHeldUnits(*r.held, table->numbering(), held));
  if (budget < header) {
    return InvalidArgument("budget " + std::to_string(budget) +
                           " is smaller than the stream header (" + std::to_string(header) +
                           " bytes)");
  }
  mesh_ = std::move(mesh);
  order_ = nullptr;
  max_level_ = r.max_level;
  units_ = table;
  held_.emplace(std::move(held));
  unit_request_ = UnitRequest{r.region, r.order, r.max_level, 0};
  selected_.clear();
  cursor_ = end_ = 0;
  const UnitPlan plan = SelectUnits(budget - header);
  return UnitSelection(0, plan, header + plan.bytes);
}

Result<StreamCursor::Selection> StreamCursor::Refine(uint64_t extra_bytes,
                                                     const std::optional<Region>& region,
                                                     std::optional<Progression> order) {
  if (!mesh_) return InvalidArgument("nothing to refine: send start or resume first");
  const bool changes = region || order;
  if (changes || units_) {
    MW_RETURN_IF_ERROR(SwitchToUnits());
    if (changes) {
      unit_request_.region = region;
      unit_request_.order = order.value_or(Progression::kQuality);
    }
    const size_t from = end_;
    const UnitPlan plan = SelectUnits(extra_bytes);
    return UnitSelection(from, plan, plan.bytes);
  }
  const Selection s = [&] {
    const ::meshwave::Selection packets = SelectPayloads(mesh_->header(), *order_, extra_bytes, end_);
    return Selection{end_, packets.next_cursor, order_->size(), packets.bytes,
                     packets.next_cursor == order_->size()};
  }();
  end_ = s.next;
  done_at_.push_back({end_, s.complete});
  return s;
}

Status StreamCursor::SwitchToUnits() {
  if (units_) return Status::Ok();
  MW_ASSIGN_OR_RETURN(const UnitTable* table, mesh_->units());
  units_ = table;
  held_.emplace(units_->nothing_held());
  // Cursors keep counting: the packets selected so far are units.
  for (size_t k = 0; k < end_; ++k) {
    selected_.push_back({(*order_)[k]});
    held_->Add({(*order_)[k]});
  }
  unit_request_.max_level = max_level_;
  order_ = nullptr;
  return Status::Ok();
}

UnitPlan StreamCursor::SelectUnits(uint64_t budget) {
  unit_request_.budget = budget;
  // The level limit was checked when the stream started.
  UnitPlan plan = *PlanUnits(*mesh_, *units_, *held_, unit_request_);
  for (const StreamUnit& u : plan.units) {
    held_->Add(u);
    selected_.push_back(u);
  }
  end_ = selected_.size();
  done_at_.push_back({end_, plan.complete});
  return plan;
}

StreamCursor::Selection StreamCursor::UnitSelection(size_t from, const UnitPlan& plan,
                                                    uint64_t bytes) const {
  return Selection{from, from + plan.units.size(), units_->UnitsBelow(max_level_), bytes,
                   plan.complete};
}

std::optional<StreamCursor::Unit> StreamCursor::Peek() const {
  if (!mesh_ || cursor_ >= end_) return std::nullopt;
  const StreamUnit unit = order_ ? StreamUnit{(*order_)[cursor_]} : selected_[cursor_];
  std::string_view payload = mesh_->payload(unit.id);
  if (!unit.whole()) payload = units_->Payload(payload, unit);
  return Unit{cursor_, unit, payload};
}

std::optional<StreamCursor::Done> StreamCursor::DoneDue() const {
  if (done_at_.empty() || cursor_ != done_at_.front().next) return std::nullopt;
  return done_at_.front();
}

}  // namespace meshwave::server
