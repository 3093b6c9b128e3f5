#include "metrics/surface_sampler.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace meshwave::metrics {

double UnitInterval(uint64_t random_bits) {
  return static_cast<double>(random_bits >> 11) * 0x1.0p-53;
}

double FaceArea(const TriMesh& mesh, const Face& face) {
  const Vec3& a = mesh.positions[face[0]];
  return 0.5 * (mesh.positions[face[1]] - a)
                   .cross(mesh.positions[face[2]] - a)
                   .norm();
}

FaceSampleCounts::FaceSampleCounts(const TriMesh& mesh, uint64_t total, bool at_least_one)
    : total_(total), at_least_one_(at_least_one) {
  for (const Face& face : mesh.faces) total_weight_ += FaceArea(mesh, face);
  if (!(total_weight_ > 0) || !std::isfinite(total_weight_)) {
    by_area_ = false;
    total_weight_ = static_cast<double>(mesh.faces.size());
  }
}

uint64_t FaceSampleCounts::Next(double face_area) {
  // The same additions in the same order as in the constructor, so the
  // last face ends exactly at total_weight_ and the counts sum to total_.
  cumulative_weight_ += by_area_ ? face_area : 1.0;
  const double scaled =
      std::min(static_cast<double>(total_),
               std::floor(static_cast<double>(total_) *
                          (cumulative_weight_ / total_weight_)));
  const auto cumulative =
      std::max(cumulative_count_, static_cast<uint64_t>(scaled));
  const uint64_t count = cumulative - cumulative_count_;
  cumulative_count_ = cumulative;
  return at_least_one_ ? std::max<uint64_t>(count, 1) : count;
}

uint64_t VisitSurfaceSamples(const TriMesh& mesh, uint64_t face_samples,
                             uint64_t seed,
                             const std::function<void(const Vec3&)>& visit, bool sparse) {
  std::mt19937_64 rng(seed);
  FaceSampleCounts counts(mesh, face_samples, /*at_least_one=*/!sparse);
  std::vector<bool> seen(sparse ? 0 : mesh.positions.size(), false);
  uint64_t visited = 0;
  for (const Face& face : mesh.faces) {
    for (const uint32_t v : face) {
      if (sparse || seen[v]) continue;
      seen[v] = true;
      visit(mesh.positions[v]);
      ++visited;
    }
    const Vec3& a = mesh.positions[face[0]];
    const Vec3 ab = mesh.positions[face[1]] - a;
    const Vec3 ac = mesh.positions[face[2]] - a;
    const uint64_t n = counts.Next(FaceArea(mesh, face));
    for (uint64_t i = 0; i < n; ++i) {
      // A uniform point of the parallelogram, folded into the triangle.
      double u = UnitInterval(rng());
      double w = UnitInterval(rng());
      if (u + w > 1) {
        u = 1 - u;
        w = 1 - w;
      }
      visit(a + u * ab + w * ac);
    }
    visited += n;
  }
  return visited;
}

}  // namespace meshwave::metrics
