// Undirected mesh edges mapped to 32-bit values in one flat table: open
// addressing, linear probing, no allocation per edge; sized for the edges
// expected and doubled when three quarters full. The std::unordered_map
// it replaces allocated a node per edge, which was most of numbering a
// large base mesh's edges (the ogre's 31 k base faces) in the decoder.
#ifndef MESHWAVE_CORE_EDGE_INDEX_TABLE_H_
#define MESHWAVE_CORE_EDGE_INDEX_TABLE_H_

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/edge_key.h"

namespace meshwave {

class EdgeIndexTable {
 public:
  // Room for `expected_edges` before it grows. (An untrusted count should
  // be capped by the caller: the table grows with the edges that come.)
  explicit EdgeIndexTable(size_t expected_edges) { Resize(SlotsFor(expected_edges)); }

  // The value of edge {a, b}, and whether it was absent and now holds
  // `value`. The reference holds until the next Emplace. a == b == 2^32 - 1
  // is not an edge (no mesh has 2^32 vertices).
  std::pair<uint32_t&, bool> Emplace(uint32_t a, uint32_t b, uint32_t value) {
    const uint64_t key = EdgeKey(a, b);
    size_t i = Slot(key);
    while (keys_[i] != kEmpty) {
      if (keys_[i] == key) return {values_[i], false};
      i = (i + 1) & mask_;
    }
    if ((size_ + 1) * 4 > keys_.size() * 3) {
      Resize(keys_.size() * 2);
      return Emplace(a, b, value);
    }
    ++size_;
    keys_[i] = key;
    values_[i] = value;
    return {values_[i], true};
  }

  size_t size() const { return size_; }

  // The value of edge {a, b}, or nullptr when absent.
  const uint32_t* Find(uint32_t a, uint32_t b) const {
    const uint64_t key = EdgeKey(a, b);
    for (size_t i = Slot(key); keys_[i] != kEmpty; i = (i + 1) & mask_) {
      if (keys_[i] == key) return &values_[i];
    }
    return nullptr;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t{0};

  static size_t SlotsFor(size_t edges) {
    size_t slots = 16;
    while (slots * 3 < edges * 4) slots *= 2;
    return slots;
  }

  void Resize(size_t slots) {
    std::vector<uint64_t> keys(slots, kEmpty);
    std::vector<uint32_t> values(slots);
    mask_ = slots - 1;
    for (size_t j = 0; j < keys_.size(); ++j) {
      if (keys_[j] == kEmpty) continue;
      size_t i = Slot(keys_[j]);
      while (keys[i] != kEmpty) i = (i + 1) & mask_;
      keys[i] = keys_[j];
      values[i] = values_[j];
    }
    keys_ = std::move(keys);
    values_ = std::move(values);
  }

  // splitmix64's finaliser: neighbouring vertex indices spread over the table.
  size_t Slot(uint64_t key) const {
    key = (key ^ (key >> 30)) * 0xBF58476D1CE4E5B9ull;
    key = (key ^ (key >> 27)) * 0x94D049BB133111EBull;
    return static_cast<size_t>(key ^ (key >> 31)) & mask_;
  }

  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t mask_ = 0;
  size_t size_ = 0;
};

}  // namespace meshwave

#endif  // MESHWAVE_CORE_EDGE_INDEX_TABLE_H_
