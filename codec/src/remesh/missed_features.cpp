#include "remesh/missed_features.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "metrics/triangle_bvh.h"
#include "core/parallel_for.h"

namespace meshwave::remesh {

MissedVertices FindMissedVertices(const TriMesh& input, const TriMesh& remesh,
                                  double threshold, double spacing,
                                  size_t max_count, int threads) {
  const metrics::TriangleBvh bvh(remesh.positions, remesh.faces, threads);
  std::vector<uint8_t> used(input.positions.size(), 0);
  for (const Face& f : input.faces) {
    for (uint32_t v : f) used[v] = 1;
  }
  std::vector<double> distance(input.positions.size(), 0);
  ParallelFor(input.positions.size(), threads, [&](size_t begin, size_t end) {
    uint32_t hint = metrics::TriangleBvh::kNoFace;
    for (size_t v = begin; v < end; ++v) {
      if (!used[v]) continue;
      const auto hit = bvh.ClosestPoint(input.positions[v], hint);
      hint = hit.face;
      distance[v] = std::sqrt(hit.distance_squared);
    }
  });
  MissedVertices out;
  std::vector<std::pair<double, uint32_t>> far;
  for (uint32_t v = 0; v < distance.size(); ++v) {
    if (distance[v] > out.max_distance) {
      out.max_distance = distance[v];
      out.farthest = v;
    }
    if (distance[v] > threshold) far.push_back({distance[v], v});
  }
  std::sort(far.begin(), far.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  const double spacing2 = spacing * spacing;
  for (const auto& [d, v] : far) {
    if (out.vertices.size() >= max_count) break;
    const Vec3& p = input.positions[v];
    bool near_picked = false;
    for (uint32_t w : out.vertices) {
      if ((input.positions[w] - p).squaredNorm() < spacing2) {
        near_picked = true;
        break;
      }
    }
    if (!near_picked) out.vertices.push_back(v);
  }
  return out;
}

}  // namespace meshwave::remesh
