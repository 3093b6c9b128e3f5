// PointKdTree: nearest-neighbour queries over a fixed set of points, used to
// match the vertices of two meshes stored in different orders.
#ifndef MESHWAVE_METRICS_POINT_KDTREE_H_
#define MESHWAVE_METRICS_POINT_KDTREE_H_

#include <cstdint>
#include <limits>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::metrics {

// An implicit, balanced k-d tree: the points are reordered so that every
// range [begin, end) has its splitting point at the middle, with smaller
// coordinates (on the range's widest axis) before it. No node storage beyond
// one axis byte per point. Built in O(n log n); immutable afterwards and
// safe to query from several threads.
class PointKdTree {
 public:
  static constexpr uint32_t kNoPoint = std::numeric_limits<uint32_t>::max();

  struct Nearest {
    uint32_t index = kNoPoint;  // into the points given to the constructor
    double distance_squared = std::numeric_limits<double>::infinity();
  };

  // Contract (asserted): fewer than 2^32 - 1 points.
  explicit PointKdTree(const std::vector<Vec3>& points);

  // The point nearest to `query`; the lowest index among equally near
  // points. With no points, index kNoPoint and an infinite distance.
  Nearest FindNearest(const Vec3& query) const;

  size_t size() const { return points_.size(); }

 private:
  void Build(uint32_t begin, uint32_t end);

  std::vector<Vec3> points_;     // in tree order
  std::vector<uint32_t> index_;  // original index of each tree slot
  std::vector<uint8_t> axis_;    // split axis of the range centred there
};

}  // namespace meshwave::metrics

#endif  // MESHWAVE_METRICS_POINT_KDTREE_H_
