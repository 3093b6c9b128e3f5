#include "metrics/closest_point_triangle.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace meshwave::metrics {
namespace {

PointOnTriangle At(const Vec3& p, const Vec3& q) {
  return {q, (p - q).squaredNorm()};
}

// Below this value of |ab × ac|² / (|ab|²·|ac|²) (sin² of the angle at a)
// the triangle is treated as its edges: the face formula divides by
// |ab × ac|², and for such slivers the edges are as accurate anyway.
constexpr double kDegenerateSin2 = 1e-24;

PointOnTriangle ClosestPointOnEdges(const Vec3& p, const Vec3& a, const Vec3& b,
                                    const Vec3& c) {
  PointOnTriangle best = ClosestPointOnSegment(p, a, b);
  for (const PointOnTriangle& other :
       {ClosestPointOnSegment(p, b, c), ClosestPointOnSegment(p, c, a)}) {
    if (other.distance_squared < best.distance_squared) best = other;
  }
  return best;
}

}  // namespace

PointOnTriangle ClosestPointOnSegment(const Vec3& p, const Vec3& a,
                                      const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return At(p, a);
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return At(p, a + t * ab);
}

PointOnTriangle ClosestPointOnTriangle(const Vec3& p, const Vec3& a,
                                       const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const double area2 = ab.cross(ac).squaredNorm();
  if (!(area2 > kDegenerateSin2 * ab.squaredNorm() * ac.squaredNorm())) {
    return ClosestPointOnEdges(p, a, b, c);
  }

  // Projections of p relative to each corner on the two edge directions.
  const Vec3 ap = p - a;
  const double ab_ap = ab.dot(ap);
  const double ac_ap = ac.dot(ap);
  if (ab_ap <= 0 && ac_ap <= 0) return At(p, a);

  const Vec3 bp = p - b;
  const double ab_bp = ab.dot(bp);
  const double ac_bp = ac.dot(bp);
  if (ab_bp >= 0 && ac_bp <= ab_bp) return At(p, b);

  const Vec3 cp = p - c;
  const double ab_cp = ab.dot(cp);
  const double ac_cp = ac.dot(cp);
  if (ac_cp >= 0 && ab_cp <= ac_cp) return At(p, c);

  // Signed areas (times |ab × ac|²) of the sub-triangles opposite each
  // corner, i.e. unnormalised barycentric coordinates of p's projection.
  // A non-positive one puts p outside that edge, in its region when its
  // projection on the edge falls between the edge's ends.
  const double bary_c = ab_ap * ac_bp - ab_bp * ac_ap;  // opposite edge ab
  if (bary_c <= 0 && ab_ap >= 0 && ab_bp <= 0) {
    return At(p, a + (ab_ap / (ab_ap - ab_bp)) * ab);  // |ab|² > 0
  }
  const double bary_b = ab_cp * ac_ap - ab_ap * ac_cp;  // opposite edge ac
  if (bary_b <= 0 && ac_ap >= 0 && ac_cp <= 0) {
    return At(p, a + (ac_ap / (ac_ap - ac_cp)) * ac);  // |ac|² > 0
  }
  const double bary_a = ab_bp * ac_cp - ab_cp * ac_bp;  // opposite edge bc
  const double along_b = ac_bp - ab_bp;                 // (p - b)·(c - b)
  const double along_c = ab_cp - ac_cp;                 // (p - c)·(b - c)
  if (bary_a <= 0 && along_b >= 0 && along_c >= 0) {
    return At(p, b + (along_b / (along_b + along_c)) * (c - b));  // |bc|²
  }

  // In exact arithmetic all three are positive here: p projects inside.
  const double sum = bary_a + bary_b + bary_c;  // = |ab × ac|² in exact math
  if (!(sum > 0)) return ClosestPointOnEdges(p, a, b, c);  // rounding guard
  return At(p, a + (bary_b / sum) * ab + (bary_c / sum) * ac);
}

}  // namespace meshwave::metrics
