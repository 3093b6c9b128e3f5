#include "metrics/point_kdtree.h"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace meshwave::metrics {
namespace {

// The ranges halve at every level, so for fewer than 2^32 points the depth
// is below 33; the query pushes at most two entries per level.
constexpr int kMaxStack = 80;

}  // namespace

PointKdTree::PointKdTree(const std::vector<Vec3>& points) {
  assert(points.size() < kNoPoint);
  const auto n = static_cast<uint32_t>(points.size());
  index_.resize(n);
  std::iota(index_.begin(), index_.end(), 0u);
  axis_.assign(n, 0);
  points_ = points;
  Build(0, n);
  for (uint32_t slot = 0; slot < n; ++slot)
    points_[slot] = points[index_[slot]];
}

// Sorts index_[begin, end) into tree order. points_ still holds the points
// in their original order while this runs.
void PointKdTree::Build(uint32_t begin, uint32_t end) {
  if (end - begin <= 1) return;
  Vec3 lo = points_[index_[begin]], hi = lo;
  for (uint32_t i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(points_[index_[i]]);
    hi = hi.cwiseMax(points_[index_[i]]);
  }
  int axis = 0;
  (hi - lo).maxCoeff(&axis);
  const uint32_t mid = begin + (end - begin) / 2;
  // Ties broken by index: the tree, and so the traversal order, does not
  // depend on the standard library's nth_element.
  std::nth_element(index_.begin() + begin, index_.begin() + mid,
                   index_.begin() + end, [&](uint32_t x, uint32_t y) {
                     const double cx = points_[x][axis];
                     const double cy = points_[y][axis];
                     return cx < cy || (cx == cy && x < y);
                   });
  axis_[mid] = static_cast<uint8_t>(axis);
  Build(begin, mid);
  Build(mid + 1, end);
}

PointKdTree::Nearest PointKdTree::FindNearest(const Vec3& query) const {
  Nearest best;
  // A range with the squared distance below which it cannot hold a point
  // (from the split planes crossed to reach it).
  struct Entry {
    uint32_t begin, end;
    double bound;
  };
  Entry stack[kMaxStack];
  int top = 0;
  if (!points_.empty()) {
    stack[top++] = {0, static_cast<uint32_t>(points_.size()), 0.0};
  }
  while (top > 0) {
    const Entry entry = stack[--top];
    // `>` rather than `>=`: an equally near point may have a lower index.
    if (entry.bound > best.distance_squared) continue;
    const uint32_t mid = entry.begin + (entry.end - entry.begin) / 2;
    const double d2 = (points_[mid] - query).squaredNorm();
    if (d2 < best.distance_squared ||
        (d2 == best.distance_squared && index_[mid] < best.index)) {
      best = {index_[mid], d2};
    }
    const double offset = query[axis_[mid]] - points_[mid][axis_[mid]];
    Entry below{entry.begin, mid, entry.bound};
    Entry above{mid + 1, entry.end, entry.bound};
    // The far side lies beyond the split plane.
    Entry& far = offset < 0 ? above : below;
    far.bound = std::max(far.bound, offset * offset);
    const Entry& near = offset < 0 ? below : above;
    assert(top + 2 <= kMaxStack);
    if (far.begin < far.end && far.bound <= best.distance_squared) {
      stack[top++] = far;
    }
    if (near.begin < near.end) stack[top++] = near;
  }
  return best;
}

}  // namespace meshwave::metrics
