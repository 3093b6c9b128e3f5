#include "asset/weld.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <numeric>
#include <vector>

namespace meshwave {

size_t WeldPositions(TriMesh& mesh) {
  const size_t n = mesh.positions.size();
  using Key = std::array<uint64_t, 3>;
  std::vector<Key> keys(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3& p = mesh.positions[i];
    keys[i] = {std::bit_cast<uint64_t>(p.x()), std::bit_cast<uint64_t>(p.y()),
               std::bit_cast<uint64_t>(p.z())};
  }
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
  });
  // The first (smallest) index of each group of equal keys represents it.
  std::vector<uint32_t> first(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    first[i] = k > 0 && keys[order[k - 1]] == keys[i] ? first[order[k - 1]] : i;
  }
  std::vector<uint32_t> renumber(n);
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    if (first[i] == i) {
      renumber[i] = static_cast<uint32_t>(kept);
      mesh.positions[kept++] = mesh.positions[i];
    }
  }
  for (size_t i = 0; i < n; ++i) renumber[i] = renumber[first[i]];
  mesh.positions.resize(kept);
  for (Face& f : mesh.faces) {
    for (uint32_t& v : f) v = renumber[v];
  }
  return n - kept;
}

}  // namespace meshwave
