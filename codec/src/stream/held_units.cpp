#include "meshwave/held_units.h"

#include <algorithm>
#include <utility>

#include "stream/packet_index.h"

namespace meshwave {

HeldUnits::HeldUnits(const StreamHeader& header, PrecinctParents parents)
    : parents_(std::move(parents)) {
  const PacketLayout layout(header);
  const uint32_t n = static_cast<uint32_t>(layout.count());
  const bool parent_contexts = header.coder == StreamCoder::k3xC;
  for (uint32_t id = 0; id < n; ++id) {
    const int j = layout.Subband(id);
    const int b = layout.Bitplane(id);
    subband_.push_back(j);
    if (layout.IsTexture(id)) {
      // A texture level is one whole image: it needs nothing.
      up_.push_back(-1);
      parent_.push_back(-1);
      part_count_.push_back(0);
      continue;
    }
    if (const int part = layout.OriginalPart(id); part >= 0) {
      // The original layer's parts go one after the other.
      up_.push_back(part > 0 ? static_cast<int>(id) - 1 : -1);
      parent_.push_back(-1);
      part_count_.push_back(0);
      continue;
    }
    if (const int k = layout.Channel(id); k >= 0) {
      // A channel's packets need their channel's only, and are never split.
      up_.push_back(layout.ChannelId(k, j, b + 1));
      parent_.push_back(j > 0 && parent_contexts ? layout.ChannelId(k, j - 1, b) : -1);
      part_count_.push_back(0);
      continue;
    }
    up_.push_back(j < 0 ? layout.BaseId(b + 1) : layout.Id(j, b + 1));
    parent_.push_back(j > 0 && parent_contexts ? layout.Id(j - 1, b) : -1);
    const bool split = layout.IsSplit(id) && static_cast<size_t>(j) < parents_.size();
    part_count_.push_back(split ? static_cast<uint32_t>(parents_[static_cast<size_t>(j)].size()) : 0);
  }
  whole_.assign(n, 0);
  parts_.assign(n, {});
}

uint32_t HeldUnits::PartCount(uint32_t id) const {
  return id < part_count_.size() ? part_count_[id] : 0;
}

bool HeldUnits::Valid(StreamUnit u) const {
  return u.id < whole_.size() && (u.whole() || u.part < part_count_[u.id]);
}

bool HeldUnits::HasShare(uint32_t id, uint32_t p) const {
  return whole_[id] || (!parts_[id].empty() && parts_[id][p]);
}

bool HeldUnits::Has(StreamUnit u) const {
  if (!Valid(u)) return false;
  return u.whole() ? whole_[u.id] != 0 : HasShare(u.id, u.part);
}

int64_t HeldUnits::FirstMissing(StreamUnit u) const {
  if (!Valid(u)) return -1;
  // Packet q held whole, or (for a part) precinct p's share of it.
  auto has = [&](int q, uint32_t p) {
    if (q < 0) return true;
    const auto id = static_cast<uint32_t>(q);
    if (whole_[id]) return true;
    return !u.whole() && part_count_[id] > 0 && HasShare(id, p);
  };
  const uint32_t p = u.whole() ? 0 : u.part;
  if (!has(up_[u.id], p)) return up_[u.id];
  const int j = subband_[u.id];
  const uint32_t parent = u.whole() || j <= 0 ? 0 : parents_[static_cast<size_t>(j)][p];
  if (!has(parent_[u.id], parent)) return parent_[u.id];
  return -1;
}

void HeldUnits::Add(StreamUnit u) {
  if (!Valid(u)) return;
  if (u.whole()) {
    whole_[u.id] = 1;
    parts_[u.id].clear();
    return;
  }
  auto& parts = parts_[u.id];
  if (whole_[u.id]) return;
  if (parts.empty()) parts.assign(part_count_[u.id], 0);
  parts[u.part] = 1;
  if (std::all_of(parts.begin(), parts.end(), [](char c) { return c != 0; })) {
    whole_[u.id] = 1;
    parts.clear();
  }
}

void HeldUnits::Clear() {
  std::fill(whole_.begin(), whole_.end(), 0);
  for (auto& parts : parts_) parts.clear();
}

}  // namespace meshwave
