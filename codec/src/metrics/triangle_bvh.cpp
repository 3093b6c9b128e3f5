#include "metrics/triangle_bvh.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "core/parallel_for.h"
#include "metrics/closest_point_triangle.h"

namespace meshwave::metrics {
namespace {

// Triangles per leaf. On igea.ply (270k faces) against itself and against
// noisy copies of itself, leaves of 2, 4 and 8 were within 10 % of each
// other; 4 was never the slowest.
constexpr uint32_t kLeafSize = 4;
// Surface-area-heuristic splits, tried on 16 bins, gave 5-10 % faster
// queries than plain median splits on igea.ply. They can be lopsided, so
// from depth kMaxSahDepth on only median splits are made: those halve the
// range, so at most 30 more levels follow (2^32 faces / 4 per leaf).
constexpr int kSahBins = 16;
constexpr int kMaxSahDepth = 32;
static_assert(kLeafSize >= 4 && kMaxSahDepth + 30 <= TriangleBvh::kMaxDepth);
constexpr double kHuge = std::numeric_limits<double>::max();
// Subtrees of at least this many faces are built beside each other when
// threads are given (a thread start costs about as much as 2,000 faces).
constexpr uint32_t kMinParallelBuild = 1u << 15;
// Below this sin² of the angle at a corner a triangle gets no normal:
// rounding makes the direction of a sliver's cross product unreliable.
constexpr double kSliverSin2 = 1e-8;

float RoundDown(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) {
    f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  }
  return f;
}

float RoundUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) {
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  }
  return f;
}

// Half the surface area of a box (the factor does not change the choice).
double HalfArea(const Vec3& lo, const Vec3& hi) {
  const Vec3 d = (hi - lo).cwiseMax(0.0);
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}

}  // namespace

struct TriangleBvh::BuildItem {
  Vec3 lo, hi, centroid;
  uint32_t face;
};

TriangleBvh::TriangleBvh(const std::vector<Vec3>& positions,
                         const std::vector<Face>& faces, int threads) {
  assert(faces.size() < kNoFace);
  const auto n = static_cast<uint32_t>(faces.size());
  if (n == 0) return;
  threads = ResolveThreads(threads);
  std::vector<BuildItem> items(n);
  ParallelFor(n, threads, [&](size_t begin, size_t end) {
    for (size_t f = begin; f < end; ++f) {
      const Face& face = faces[f];
      assert(face[0] < positions.size() && face[1] < positions.size() &&
             face[2] < positions.size());
      const Vec3& a = positions[face[0]];
      const Vec3& b = positions[face[1]];
      const Vec3& c = positions[face[2]];
      items[f] = {a.cwiseMin(b).cwiseMin(c), a.cwiseMax(b).cwiseMax(c),
                  (a + b + c) / 3.0, static_cast<uint32_t>(f)};
    }
  });
  nodes_.reserve(2 * (n / kLeafSize + 1));
  Build(items, 0, n, 0, threads, nodes_, depth_);
  // Build only permutes `items`, and a leaf owns the slots [begin, end) it
  // had when it was made, so the final item order is the leaf order.
  triangles_.resize(n);
  slot_of_face_.resize(n);
  ParallelFor(n, threads, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const uint32_t f = items[slot].face;
      const Face& face = faces[f];
      const Vec3& a = positions[face[0]];
      const Vec3& b = positions[face[1]];
      const Vec3& c = positions[face[2]];
      Vec3 normal = (b - a).cross(c - a);
      const double length2 = normal.squaredNorm();
      const bool reliable =
          std::isfinite(length2) &&
          length2 > kSliverSin2 * (b - a).squaredNorm() * (c - a).squaredNorm();
      normal = reliable ? Vec3(normal / std::sqrt(length2)) : Vec3(Vec3::Zero());
      triangles_[slot] = {a, b, c, normal, f};
      slot_of_face_[f] = static_cast<uint32_t>(slot);
    }
  });
}

uint32_t TriangleBvh::Build(std::vector<BuildItem>& items, uint32_t begin,
                            uint32_t end, int depth, int threads,
                            std::vector<Node>& nodes, int& max_depth) {
  const auto index = static_cast<uint32_t>(nodes.size());
  nodes.push_back({});
  Vec3 lo = items[begin].lo, hi = items[begin].hi;
  for (uint32_t i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(items[i].lo);
    hi = hi.cwiseMax(items[i].hi);
  }
  Node node{};
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = RoundDown(lo[k]);
    node.hi[k] = RoundUp(hi[k]);
  }
  if (end - begin <= kLeafSize) {
    max_depth = std::max(max_depth, depth);
    // Face order inside a leaf fixes which of equally near faces wins.
    std::sort(
        items.begin() + begin, items.begin() + end,
        [](const BuildItem& x, const BuildItem& y) { return x.face < y.face; });
    node.start = begin;
    node.count = end - begin;
    nodes[index] = node;
    return index;
  }
  const uint32_t mid = Split(items, begin, end, depth < kMaxSahDepth);
  node.count = 0;
  nodes[index] = node;
  if (threads > 1 && end - begin >= kMinParallelBuild) {
    // The right subtree into a vector of its own beside the left one, then
    // appended after it with its internal nodes' child indices moved.
    std::vector<Node> right;
    int right_depth = 0;
    const int left_threads = threads / 2;
    ParallelInvoke(
        2,
        [&] {
          Build(items, begin, mid, depth + 1, left_threads, nodes, max_depth);
        },
        [&] {
          right.reserve(2 * ((end - mid) / kLeafSize + 1));
          Build(items, mid, end, depth + 1, threads - left_threads, right,
                right_depth);
        });
    const auto base = static_cast<uint32_t>(nodes.size());
    for (Node child : right) {
      if (child.count == 0) child.start += base;
      nodes.push_back(child);
    }
    max_depth = std::max(max_depth, right_depth);
    nodes[index].start = base;
    return index;
  }
  Build(items, begin, mid, depth + 1, 1, nodes, max_depth);  // at index + 1
  const uint32_t right = Build(items, mid, end, depth + 1, 1, nodes, max_depth);
  nodes[index].start = right;
  return index;
}

uint32_t TriangleBvh::Split(std::vector<BuildItem>& items, uint32_t begin,
                            uint32_t end, bool try_sah) {
  Vec3 centroid_lo = items[begin].centroid, centroid_hi = centroid_lo;
  for (uint32_t i = begin + 1; i < end; ++i) {
    centroid_lo = centroid_lo.cwiseMin(items[i].centroid);
    centroid_hi = centroid_hi.cwiseMax(items[i].centroid);
  }
  int axis = 0;
  const double extent = (centroid_hi - centroid_lo).maxCoeff(&axis);
  const double origin = centroid_lo[axis];

  if (try_sah && extent > 0 && std::isfinite(extent)) {
    // Binned surface-area heuristic: bin the centroids along the axis and
    // cut where (faces × box area) summed over both sides is least.
    struct Bin {
      Vec3 lo = Vec3::Constant(kHuge), hi = Vec3::Constant(-kHuge);
      uint32_t count = 0;
    };
    const auto bin_of = [&](const BuildItem& item) {
      const int b = static_cast<int>(kSahBins *
                                     ((item.centroid[axis] - origin) / extent));
      return std::clamp(b, 0, kSahBins - 1);
    };
    Bin bins[kSahBins];
    for (uint32_t i = begin; i < end; ++i) {
      Bin& bin = bins[bin_of(items[i])];
      bin.lo = bin.lo.cwiseMin(items[i].lo);
      bin.hi = bin.hi.cwiseMax(items[i].hi);
      ++bin.count;
    }
    double cost_above[kSahBins] = {};  // of bins [k, kSahBins)
    Bin above;
    for (int k = kSahBins - 1; k > 0; --k) {
      above = {above.lo.cwiseMin(bins[k].lo), above.hi.cwiseMax(bins[k].hi),
               above.count + bins[k].count};
      cost_above[k] = above.count * HalfArea(above.lo, above.hi);
    }
    Bin below;
    double best_cost = std::numeric_limits<double>::infinity();
    int best_cut = 0;
    for (int k = 1; k < kSahBins; ++k) {
      below = {below.lo.cwiseMin(bins[k - 1].lo),
               below.hi.cwiseMax(bins[k - 1].hi),
               below.count + bins[k - 1].count};
      if (below.count == 0 || below.count == end - begin) continue;
      const double cost =
          below.count * HalfArea(below.lo, below.hi) + cost_above[k];
      if (cost < best_cost) {
        best_cost = cost;
        best_cut = k;
      }
    }
    if (best_cut > 0) {
      // Stable, so the tree is the same with every standard library.
      const auto cut = std::stable_partition(
          items.begin() + begin, items.begin() + end,
          [&](const BuildItem& item) { return bin_of(item) < best_cut; });
      return static_cast<uint32_t>(cut - items.begin());
    }
  }
  // Median split: always balanced, also when all centroids coincide. Ties
  // are broken by face index so the halves do not depend on the library.
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid,
                   items.begin() + end,
                   [axis](const BuildItem& x, const BuildItem& y) {
                     const double cx = x.centroid[axis];
                     const double cy = y.centroid[axis];
                     return cx < cy || (cx == cy && x.face < y.face);
                   });
  return mid;
}

void TriangleBvh::TestLeaf(const Node& node, const Vec3& p, Hit& best) const {
  for (uint32_t i = node.start; i < node.start + node.count; ++i) {
    const Triangle& t = triangles_[i];
    const double plane = t.normal.dot(p - t.a);
    if (plane * plane >= best.distance_squared) continue;
    const PointOnTriangle q = ClosestPointOnTriangle(p, t.a, t.b, t.c);
    if (q.distance_squared < best.distance_squared) {
      best = {q.distance_squared, t.face, q.point};
    }
  }
}

TriangleBvh::Hit TriangleBvh::ClosestPoint(const Vec3& p,
                                           uint32_t hint_face) const {
  Hit best;
  if (hint_face < slot_of_face_.size()) {
    const Triangle& t = triangles_[slot_of_face_[hint_face]];
    const PointOnTriangle q = ClosestPointOnTriangle(p, t.a, t.b, t.c);
    best = {q.distance_squared, t.face, q.point};
  }
  if (nodes_.empty()) return best;

  // Depth-first, nearer child first; a subtree is skipped once its box is
  // no nearer than the best triangle found so far.
  struct Entry {
    uint32_t node;
    double distance_squared;
  };
  Entry stack[kMaxStack];
  int top = 0;
  stack[top++] = {0, BoxDistanceSquared(nodes_[0].lo, nodes_[0].hi, p)};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.distance_squared >= best.distance_squared) continue;
    const Node& node = nodes_[entry.node];
    if (node.count > 0) {
      TestLeaf(node, p, best);
      continue;
    }
    const Node& left = nodes_[entry.node + 1];
    const Node& right = nodes_[node.start];
    Entry near{entry.node + 1, BoxDistanceSquared(left.lo, left.hi, p)};
    Entry far{node.start, BoxDistanceSquared(right.lo, right.hi, p)};
    if (far.distance_squared < near.distance_squared) std::swap(near, far);
    assert(top + 2 <= kMaxStack);
    if (far.distance_squared < best.distance_squared) stack[top++] = far;
    if (near.distance_squared < best.distance_squared) stack[top++] = near;
  }
  return best;
}

}  // namespace meshwave::metrics
