// SymmetricSurfaceDistance (meshwave/metrics.h): samples on one mesh,
// closest points on the other through a TriangleBvh, both ways.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/parallel_for.h"
#include "meshwave/mesh_stats.h"
#include "meshwave/metrics.h"
#include "metrics/input_checks.h"
#include "metrics/surface_sampler.h"
#include "metrics/triangle_bvh.h"

namespace meshwave {
namespace {

// Caps the face samples of one mesh. At about 0.5 µs a query that is
// already twenty minutes; above it a typo in --samples-per-face is likelier
// than a wish.
constexpr double kMaxFaceSamples = 2147483648.0;  // 2^31
// Mixed into the seed for the samples on B so the two directions do not
// draw the same random sequence.
constexpr uint64_t kSeedMixForB = 0x9e3779b97f4a7c15ULL;

struct OneSided {
  double rms = 0, mean = 0, max = 0;
  size_t samples = 0;
};

// Samples are queried in batches, each split into fixed chunks measured on
// the threads side by side; the chunks' sums are added in chunk order, so
// the result does not depend on the thread count. A batch of points is
// 24 MiB at most, whatever the sample count.
constexpr size_t kChunk = 4096;
constexpr size_t kBatch = 256 * kChunk;

struct ChunkSums {
  double sum = 0, sum_squared = 0, max = 0;
};

// Distances from the samples of `from` to the surface indexed by `to`;
// sparse sampling when every face and vertex would exceed `max_samples`.
OneSided Measure(const TriMesh& from, const metrics::TriangleBvh& to,
                 uint64_t face_samples, uint64_t seed, uint64_t max_samples,
                 int threads) {
  const bool sparse =
      max_samples > 0 && face_samples + from.positions.size() > max_samples;
  if (sparse) face_samples = max_samples;
  double sum = 0, sum_squared = 0, max = 0;
  std::vector<Vec3> batch;
  batch.reserve(kBatch);
  std::vector<ChunkSums> chunks;
  const auto flush = [&] {
    chunks.assign((batch.size() + kChunk - 1) / kChunk, ChunkSums{});
    ParallelFor(
        chunks.size(), threads,
        [&](size_t first, size_t last) {
          for (size_t c = first; c < last; ++c) {
            // Consecutive samples are close, so the face hit last is a good
            // first guess and lets the BVH prune almost everything at once.
            uint32_t hint = metrics::TriangleBvh::kNoFace;
            ChunkSums& s = chunks[c];
            const size_t end = std::min(batch.size(), (c + 1) * kChunk);
            for (size_t i = c * kChunk; i < end; ++i) {
              const metrics::TriangleBvh::Hit hit = to.ClosestPoint(batch[i], hint);
              hint = hit.face;
              const double d = std::sqrt(hit.distance_squared);
              s.sum += d;
              s.sum_squared += hit.distance_squared;
              s.max = std::max(s.max, d);
            }
          }
        },
        1);
    for (const ChunkSums& s : chunks) {
      sum += s.sum;
      sum_squared += s.sum_squared;
      max = std::max(max, s.max);
    }
    batch.clear();
  };
  const uint64_t n = metrics::VisitSurfaceSamples(
      from, face_samples, seed,
      [&](const Vec3& p) {
        batch.push_back(p);
        if (batch.size() == kBatch) flush();
      },
      sparse);
  if (!batch.empty()) flush();
  OneSided out;
  out.samples = static_cast<size_t>(n);
  out.rms = std::sqrt(sum_squared / static_cast<double>(n));
  out.mean = sum / static_cast<double>(n);
  out.max = max;
  return out;
}

}  // namespace

double SurfaceDistance::PsnrDb(double distance) const {
  return ::meshwave::PsnrDb(diagonal, distance);
}

Result<SurfaceDistance> SymmetricSurfaceDistance(
    const TriMesh& a, const TriMesh& b, const SurfaceDistanceOptions& options) {
  MW_RETURN_IF_ERROR(metrics::CheckSurface(a, "mesh A"));
  MW_RETURN_IF_ERROR(metrics::CheckSurface(b, "mesh B"));
  constexpr size_t kMaxFaces = metrics::TriangleBvh::kNoFace - 1;
  if (a.faces.size() > kMaxFaces || b.faces.size() > kMaxFaces) {
    return InvalidArgument("surface distance: more than 2^32 - 2 faces");
  }
  if (!std::isfinite(options.samples_per_face) ||
      options.samples_per_face < 0) {
    return InvalidArgument(
        "samples per face must be a finite number >= 0, got " +
        std::to_string(options.samples_per_face));
  }
  const double denser =
      static_cast<double>(std::max(a.faces.size(), b.faces.size()));
  const double face_samples =
      std::max(static_cast<double>(options.min_samples),
               std::ceil(options.samples_per_face * denser));
  if (face_samples > kMaxFaceSamples) {
    return InvalidArgument("surface distance: " + std::to_string(face_samples) +
                           " samples per mesh asked for, more than 2^31");
  }

  // One direction after the other, each on all threads: only one index is
  // held at a time (for a 10 M-face scan and its remesh, over a GiB less
  // than two side by side).
  const auto count = static_cast<uint64_t>(face_samples);
  const int threads = options.threads;
  const OneSided ab = Measure(a, metrics::TriangleBvh(b.positions, b.faces, threads),
                              count, options.seed, options.max_samples, threads);
  const OneSided ba =
      Measure(b, metrics::TriangleBvh(a.positions, a.faces, threads), count,
              options.seed ^ kSeedMixForB, options.max_samples, threads);

  SurfaceDistance out;
  out.rms_ab = ab.rms;
  out.rms_ba = ba.rms;
  out.rms = std::max(ab.rms, ba.rms);
  out.hausdorff_ab = ab.max;
  out.hausdorff_ba = ba.max;
  out.hausdorff = std::max(ab.max, ba.max);
  out.mean_ab = ab.mean;
  out.mean_ba = ba.mean;
  out.mean = std::max(ab.mean, ba.mean);
  out.diagonal = BoundingBox(a.positions).Diagonal();
  out.samples_a = ab.samples;
  out.samples_b = ba.samples;
  return out;
}

}  // namespace meshwave
