// The filtered queries of TriangleBvh: closest point over accepted faces,
// and the accepted crossing of a line nearest to its origin. Kept apart from
// triangle_bvh.cpp so the metrics' hot path is untouched.
#include <Eigen/Geometry>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <utility>

#include "metrics/closest_point_triangle.h"
#include "metrics/triangle_bvh.h"

namespace meshwave::metrics {
namespace {

// Barycentric slack of the line-triangle test: a line through the edge
// shared by two faces must hit one of them despite rounding.
constexpr double kBarycentricSlack = 1e-9;

// The smallest |t| at which the line origin + t·direction is inside the box,
// or infinity when the line misses it.
double LineBoxReach(const float lo[3], const float hi[3], const Vec3& origin,
                    const Vec3& direction) {
  double t0 = -std::numeric_limits<double>::infinity();
  double t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double l = lo[k], h = hi[k];
    if (direction[k] == 0) {
      if (origin[k] < l || origin[k] > h) {
        return std::numeric_limits<double>::infinity();
      }
      continue;
    }
    double a = (l - origin[k]) / direction[k];
    double b = (h - origin[k]) / direction[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return std::numeric_limits<double>::infinity();
  }
  if (t0 <= 0 && t1 >= 0) return 0;
  return t0 > 0 ? t0 : -t1;
}

}  // namespace

void TriangleBvh::TestLeafIf(const Node& node, const Vec3& p,
                             const FaceFilter& accept, Hit& best) const {
  for (uint32_t i = node.start; i < node.start + node.count; ++i) {
    const Triangle& t = triangles_[i];
    const double plane = t.normal.dot(p - t.a);
    if (plane * plane >= best.distance_squared) continue;
    if (!accept(t.face)) continue;
    const PointOnTriangle q = ClosestPointOnTriangle(p, t.a, t.b, t.c);
    if (q.distance_squared < best.distance_squared) {
      best = {q.distance_squared, t.face, q.point};
    }
  }
}

TriangleBvh::Hit TriangleBvh::ClosestPointIf(
    const Vec3& p, uint32_t hint_face, const FaceFilter& accept,
    double max_distance_squared) const {
  Hit best;
  best.distance_squared = max_distance_squared;
  if (hint_face < slot_of_face_.size() && accept(hint_face)) {
    const Triangle& t = triangles_[slot_of_face_[hint_face]];
    const PointOnTriangle q = ClosestPointOnTriangle(p, t.a, t.b, t.c);
    if (q.distance_squared < best.distance_squared) {
      best = {q.distance_squared, t.face, q.point};
    }
  }
  if (nodes_.empty()) return best;
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
      TestLeafIf(node, p, accept, best);
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
  if (best.face == kNoFace)
    best.distance_squared = std::numeric_limits<double>::infinity();
  return best;
}

TriangleBvh::LineHit TriangleBvh::NearestLineHit(
    const Vec3& origin, const Vec3& direction, double max_abs_t,
    const FaceFilter& accept) const {
  LineHit best;
  if (nodes_.empty() || !(direction.squaredNorm() > 0)) return best;
  // Entries carry the smallest |t| of their box; a box no nearer than the
  // best crossing (or beyond max_abs_t) is skipped.
  double limit = max_abs_t;
  struct Entry {
    uint32_t node;
    double reach;
  };
  Entry stack[kMaxStack];
  int top = 0;
  const double root =
      LineBoxReach(nodes_[0].lo, nodes_[0].hi, origin, direction);
  if (!(root <= limit)) return best;
  stack[top++] = {0, root};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.reach > limit) continue;
    const Node& node = nodes_[entry.node];
    if (node.count > 0) {
      for (uint32_t i = node.start; i < node.start + node.count; ++i) {
        const Triangle& tri = triangles_[i];
        // Möller-Trumbore, for both signs of t.
        const Vec3 e1 = tri.b - tri.a;
        const Vec3 e2 = tri.c - tri.a;
        const Vec3 pvec = direction.cross(e2);
        const double det = e1.dot(pvec);
        const double scale = e1.norm() * e2.norm() * direction.norm();
        if (!(std::abs(det) > 1e-14 * scale)) continue;
        const double inv = 1.0 / det;
        const Vec3 s = origin - tri.a;
        const double u = s.dot(pvec) * inv;
        if (u < -kBarycentricSlack || u > 1 + kBarycentricSlack) continue;
        const Vec3 qvec = s.cross(e1);
        const double v = direction.dot(qvec) * inv;
        if (v < -kBarycentricSlack || u + v > 1 + kBarycentricSlack) continue;
        const double t = e2.dot(qvec) * inv;
        if (std::abs(t) > limit || std::abs(t) >= std::abs(best.t)) continue;
        if (!accept(tri.face)) continue;
        best.t = t;
        best.face = tri.face;
        best.point = origin + t * direction;
        limit = std::abs(t);
      }
      continue;
    }
    const Node& left = nodes_[entry.node + 1];
    const Node& right = nodes_[node.start];
    Entry near{entry.node + 1,
               LineBoxReach(left.lo, left.hi, origin, direction)};
    Entry far{node.start, LineBoxReach(right.lo, right.hi, origin, direction)};
    if (far.reach < near.reach) std::swap(near, far);
    assert(top + 2 <= kMaxStack);
    if (far.reach <= limit) stack[top++] = far;
    if (near.reach <= limit) stack[top++] = near;
  }
  return best;
}

}  // namespace meshwave::metrics
