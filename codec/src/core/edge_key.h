// 64-bit keys for mesh edges, for hash maps and sorted lists of edges.
#ifndef MESHWAVE_CORE_EDGE_KEY_H_
#define MESHWAVE_CORE_EDGE_KEY_H_

#include <cstdint>
#include <utility>

namespace meshwave {

// The directed edge a -> b: a in the high half, so sorted keys group the
// edges leaving one vertex.
constexpr uint64_t DirectedEdgeKey(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

// The key of b -> a given the key of a -> b.
constexpr uint64_t ReversedEdgeKey(uint64_t key) { return (key << 32) | (key >> 32); }

// The undirected edge {a, b}: the same key for a -> b and b -> a.
constexpr uint64_t EdgeKey(uint32_t a, uint32_t b) {
  if (a > b) std::swap(a, b);
  return DirectedEdgeKey(a, b);
}

}  // namespace meshwave

#endif  // MESHWAVE_CORE_EDGE_KEY_H_
