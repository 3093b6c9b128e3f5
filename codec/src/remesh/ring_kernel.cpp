// RingKernelPoint: projections onto convex sets in the tangent plane.
#include "remesh/ring_kernel.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>

namespace meshwave::remesh {
namespace {

constexpr int kKernelIterations = 32;

}  // namespace

Vec3 RingKernelPoint(std::span<const Vec3> positions, const Vec3& start,
                     const Vec3& n, std::span<const uint32_t> ring) {
  const Vec3 t1 = n.unitOrthogonal();
  const Vec3 t2 = n.cross(t1);
  std::array<Eigen::Vector2d, kMaxKernelRing> r;
  const size_t k = std::min(ring.size(), kMaxKernelRing);
  for (size_t i = 0; i < k; ++i) {
    const Vec3 d = positions[ring[i]] - start;
    r[i] = {d.dot(t1), d.dot(t2)};
  }
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (int iteration = 0; iteration < kKernelIterations; ++iteration) {
    bool inside = true;
    for (size_t i = 0; i < k; ++i) {
      const Eigen::Vector2d& a = r[i];
      const Eigen::Vector2d& b = r[(i + 1) % k];
      const Eigen::Vector2d e = b - a;
      const double length = e.norm();
      if (!(length > 0)) continue;
      // Left of a -> b by at least kKernelMargin · |ab|.
      const Eigen::Vector2d inward(-e.y() / length, e.x() / length);
      const double height = inward.dot(x - a);
      const double want = kKernelMargin * length;
      if (height < want) {
        x += (want - height) * inward;
        inside = false;
      }
    }
    if (inside) break;
  }
  return start + x.x() * t1 + x.y() * t2;
}

}  // namespace meshwave::remesh
