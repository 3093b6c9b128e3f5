#include "remesh/coincident_vertices.h"

#include <bit>
#include <cstdint>
#include <unordered_map>

#include "core/hash_mix.h"

namespace meshwave::remesh {
namespace {

// A collision left after this many rounds would need vertices on top of one
// another with identical neighbourhoods; not worth more.
constexpr int kMaxRounds = 8;
constexpr double kStep = 0.01;

struct FloatKey {
  uint32_t x, y, z;
  bool operator==(const FloatKey&) const = default;
};
struct FloatKeyHash {
  size_t operator()(const FloatKey& k) const { return HashTriple(k.x, k.y, k.z); }
};

FloatKey KeyOf(const Vec3& p) {
  return {std::bit_cast<uint32_t>(static_cast<float>(p.x())),
          std::bit_cast<uint32_t>(static_cast<float>(p.y())),
          std::bit_cast<uint32_t>(static_cast<float>(p.z()))};
}

}  // namespace

size_t SeparateCoincidentVertices(std::vector<Vec3>& positions,
                                  const std::vector<Face>& faces) {
  size_t moves = 0;
  for (int round = 0; round < kMaxRounds; ++round) {
    std::unordered_map<FloatKey, uint32_t, FloatKeyHash> seen;
    seen.reserve(positions.size());
    std::vector<uint8_t> duplicate(positions.size(), 0);
    bool any = false;
    for (uint32_t v = 0; v < positions.size(); ++v) {
      if (!seen.emplace(KeyOf(positions[v]), v).second) {
        duplicate[v] = 1;
        any = true;
      }
    }
    if (!any) break;
    std::vector<Vec3> centroid(positions.size(), Vec3::Zero());
    std::vector<uint32_t> count(positions.size(), 0);
    for (const Face& f : faces) {
      const Vec3 c =
          (positions[f[0]] + positions[f[1]] + positions[f[2]]) / 3.0;
      for (uint32_t v : f) {
        if (!duplicate[v]) continue;
        centroid[v] += c;
        ++count[v];
      }
    }
    for (uint32_t v = 0; v < positions.size(); ++v) {
      if (!duplicate[v] || count[v] == 0) continue;
      const Vec3 target = centroid[v] / count[v];
      positions[v] += kStep * (target - positions[v]);
      ++moves;
    }
  }
  return moves;
}

}  // namespace meshwave::remesh
