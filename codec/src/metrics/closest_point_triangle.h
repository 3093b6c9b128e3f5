// Closest point of a triangle to a query point, the primitive under every
// point-to-surface distance in the metrics.
#ifndef MESHWAVE_METRICS_CLOSEST_POINT_TRIANGLE_H_
#define MESHWAVE_METRICS_CLOSEST_POINT_TRIANGLE_H_

#include "meshwave/mesh.h"

namespace meshwave::metrics {

struct PointOnTriangle {
  Vec3 point = Vec3::Zero();    // closest point of the triangle
  double distance_squared = 0;  // ||p - point||²
};

// Closest point of the triangle (a, b, c), interior included, to `p`.
// Classifies p into the Voronoi regions of the three vertices, three edges
// and the face, in that order (the usual region tests). Degenerate triangles
// (collinear or coincident corners) are handled as the union of their three
// edges, so the result is always finite for finite input.
PointOnTriangle ClosestPointOnTriangle(const Vec3& p, const Vec3& a,
                                       const Vec3& b, const Vec3& c);

// Closest point of the segment [a, b] (a point when a == b) to `p`.
PointOnTriangle ClosestPointOnSegment(const Vec3& p, const Vec3& a,
                                      const Vec3& b);

}  // namespace meshwave::metrics

#endif  // MESHWAVE_METRICS_CLOSEST_POINT_TRIANGLE_H_
