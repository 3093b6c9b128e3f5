#include "unit_table.h"

#include <utility>

#include "meshwave/progression.h"

namespace meshwave::server {

UnitTable::UnitTable(StreamPrecincts precincts, const StreamHeader& header)
    : precincts_(std::move(precincts)),
      nothing_held_(header, precincts_.parents()),
      numbering_(nothing_held_) {}

Result<std::unique_ptr<const UnitTable>> UnitTable::Build(
    const StreamHeader& header, const std::vector<std::string_view>& payloads) {
  MW_ASSIGN_OR_RETURN(StreamPrecincts precincts, StreamPrecincts::Create(header));
  std::unique_ptr<UnitTable> t(new UnitTable(std::move(precincts), header));
  for (uint32_t id = 0; id < payloads.size(); ++id) {
    std::vector<std::string_view> parts;
    if (t->nothing_held_.PartCount(id) > 0) {
      MW_ASSIGN_OR_RETURN(parts, PacketParts(t->nothing_held_, id, payloads[id]));
    }
    std::vector<uint32_t> lengths, offsets;
    for (std::string_view part : parts) {
      lengths.push_back(static_cast<uint32_t>(part.size()));
      offsets.push_back(static_cast<uint32_t>(part.data() - payloads[id].data()));
    }
    t->part_lengths_.push_back(std::move(lengths));
    t->part_offsets_.push_back(std::move(offsets));
  }
  const int levels = static_cast<int>(header.transform.levels);
  for (int max_level = -1; max_level <= levels; ++max_level) {
    size_t units = 0;
    for (uint32_t id : PacketOrder(header, Progression::kResolution, max_level)) {
      units += std::max<size_t>(1, t->part_lengths_[id].size());
    }
    t->units_below_.push_back(units);
  }
  return std::unique_ptr<const UnitTable>(std::move(t));
}

std::string_view UnitTable::Payload(std::string_view packet_payload, StreamUnit u) const {
  if (u.whole()) return packet_payload;
  return packet_payload.substr(part_offsets_[u.id][u.part], part_lengths_[u.id][u.part]);
}

uint64_t UnitTable::Length(uint64_t packet_length, StreamUnit u) const {
  return u.whole() ? packet_length : part_lengths_[u.id][u.part];
}

size_t UnitTable::UnitsBelow(int max_level) const {
  const size_t i = static_cast<size_t>(max_level + 1);
  return units_below_[std::min(i, units_below_.size() - 1)];
}

}  // namespace meshwave::server
