#include "remesh/ring_kernel.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <numeric>
#include <vector>

namespace meshwave::remesh {
namespace {

// A star-shaped ring with a deep reflex corner at (0, 1): its kernel is
// the wedge y >= 1 + 1.5 |x| below y = 3, and its centroid is the reflex
// corner itself, where the faces to that corner have no area.
std::vector<Vec3> DentedRing() {
  return {{-2, -2, 0}, {0, 1, 0}, {2, -2, 0}, {1, 3, 0}, {0, 3, 0}, {-1, 3, 0}};
}

// Smallest height of p over a ring edge (seen from n), as a fraction of
// that edge's length; negative when p is on the wrong side of one.
double WorstHeight(const std::vector<Vec3>& ring, const Vec3& p,
                   const Vec3& n) {
  double worst = 1e300;
  for (size_t i = 0; i < ring.size(); ++i) {
    const Vec3& a = ring[i];
    const Vec3& b = ring[(i + 1) % ring.size()];
    const double twice_area = (a - p).cross(b - p).dot(n);
    worst = std::min(worst, twice_area / (b - a).squaredNorm());
  }
  return worst;
}

std::vector<uint32_t> Indices(size_t n) {
  std::vector<uint32_t> out(n);
  std::iota(out.begin(), out.end(), 0u);
  return out;
}

Vec3 Centroid(const std::vector<Vec3>& ring) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : ring) c += p;
  return c / static_cast<double>(ring.size());
}

TEST(RingKernelTest, FindsTheKernelOfANonConvexRingFromItsCentroid) {
  const std::vector<Vec3> ring = DentedRing();
  const Vec3 n(0, 0, 1);
  const Vec3 centroid = Centroid(ring);
  ASSERT_LE(WorstHeight(ring, centroid, n), 0.0);
  const Vec3 p = RingKernelPoint(ring, centroid, n, Indices(ring.size()));
  EXPECT_NEAR(p.z(), 0.0, 1e-12);
  EXPECT_GT(p.y(), 1 + 1.5 * std::abs(p.x()));
  // Every face to the ring stands up by about kKernelMargin of its edge.
  EXPECT_GT(WorstHeight(ring, p, n), 0.9 * kKernelMargin);
}

TEST(RingKernelTest, KeepsAPointAlreadyInTheKernel) {
  const std::vector<Vec3> ring = DentedRing();
  const Vec3 inside(0, 2, 0);
  ASSERT_GT(WorstHeight(ring, inside, Vec3(0, 0, 1)), kKernelMargin);
  const Vec3 p =
      RingKernelPoint(ring, inside, Vec3(0, 0, 1), Indices(ring.size()));
  EXPECT_LT((p - inside).norm(), 1e-15);
}

TEST(RingKernelTest, WorksInATiltedPlaneThroughTheStart) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, -0.5).normalized()).toRotationMatrix();
  std::vector<Vec3> ring = DentedRing();
  for (Vec3& p : ring) p = r * p + Vec3(3, -1, 2);
  const Vec3 n = r * Vec3(0, 0, 1);
  // Start off the ring's plane: the result is in the plane through start.
  const Vec3 start = Centroid(ring) + 0.25 * n;
  const Vec3 p = RingKernelPoint(ring, start, n, Indices(ring.size()));
  EXPECT_NEAR((p - start).dot(n), 0.0, 1e-12);
  EXPECT_GT(WorstHeight(ring, p - 0.25 * n, n), 0.9 * kKernelMargin);
}

}  // namespace
}  // namespace meshwave::remesh
