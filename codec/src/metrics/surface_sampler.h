// Sample points on a triangle mesh surface for the METRO-style distance.
#ifndef MESHWAVE_METRICS_SURFACE_SAMPLER_H_
#define MESHWAVE_METRICS_SURFACE_SAMPLER_H_

#include <cstdint>
#include <functional>

#include "meshwave/mesh.h"

namespace meshwave::metrics {

// Uniform double in [0, 1) from the top 53 bits of a 64-bit draw. Written
// out rather than std::uniform_real_distribution, whose algorithm the
// standard leaves to the library, so samples are the same everywhere.
double UnitInterval(uint64_t random_bits);

// How many face samples face f gets when `total` samples are spread over
// the faces by area: cumulative areas are scaled to `total` and rounded
// down, and face f gets the difference across it, but at least 1. So the
// faces together get at least `total` (more only through the minimum of 1).
// Without any area (all faces degenerate) faces count equally.
class FaceSampleCounts {
 public:
  // `at_least_one` false: a face may get none (sparse sampling of a mesh
  // with more faces than samples).
  FaceSampleCounts(const TriMesh& mesh, uint64_t total, bool at_least_one = true);
  // Call once per face, in face order.
  uint64_t Next(double face_area);

 private:
  uint64_t total_;
  double total_weight_ = 0;
  double cumulative_weight_ = 0;
  uint64_t cumulative_count_ = 0;
  bool by_area_ = true;
  bool at_least_one_ = true;
};

double FaceArea(const TriMesh& mesh, const Face& face);

// Calls `visit(point)` for every sample of `mesh`: walking the faces in
// order, first each corner not seen before (so every referenced vertex
// once, unreferenced ones never), then the face's share of `face_samples`
// uniform random points inside it (std::mt19937_64 seeded with `seed`).
// `sparse`: no vertex samples, and faces whose share rounds to zero get
// none (exactly `face_samples` points by area, for meshes too large to
// sample every face). Consecutive samples are near each other, which the
// caller can exploit. Returns the number of samples. Contract: face
// indices are in range.
uint64_t VisitSurfaceSamples(const TriMesh& mesh, uint64_t face_samples,
                             uint64_t seed,
                             const std::function<void(const Vec3&)>& visit,
                             bool sparse = false);

}  // namespace meshwave::metrics

#endif  // MESHWAVE_METRICS_SURFACE_SAMPLER_H_
