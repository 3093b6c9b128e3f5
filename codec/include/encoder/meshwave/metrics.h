// Error metrics between two meshes: per-vertex error with PSNR (same indices
// or matched by nearest neighbour) and the METRO-style sampled symmetric
// surface distance (RMS, mean and Hausdorff). All functions validate their
// input (sizes, face indices, finite coordinates) and return InvalidArgument
// instead of crashing, so they are safe on meshes read from untrusted files.
// Results are deterministic: the same input and seed give the same numbers
// on every run. The random sample parameters are the same on every platform
// (std::mt19937_64 and an explicit conversion to doubles); the distances
// computed from them agree across compilers up to floating-point rounding
// (for example where a compiler fuses multiply-adds).
#ifndef MESHWAVE_METRICS_H_
#define MESHWAVE_METRICS_H_

#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

// PSNR in dB of an error `rms` relative to `peak`: 20·log10(peak / rms).
// +infinity when rms == 0 (identical data), so callers can print it as such.
double PsnrDb(double peak, double rms);

// Statistics of the distances ||reference_i - test_match(i)||, one per
// reference vertex.
struct VertexErrorStats {
  double rms = 0;      // sqrt(mean of squared distances)
  double max = 0;      // largest distance
  double mean = 0;     // mean distance
  double psnr_db = 0;  // PsnrDb(peak, rms); +infinity when rms == 0
  double peak = 0;     // the peak the PSNR is relative to
  size_t count = 0;    // number of reference vertices measured
  // False: vertex i was compared with test vertex i. True: with the test
  // vertex nearest to it.
  bool matched_by_nearest = false;
  // How many distinct test vertices were used as matches. Equals `count`
  // for same-index matching; for nearest matching a value below `count`
  // means the matching is not a permutation (test vertices used twice).
  size_t distinct_matches = 0;
};

// Compares vertex i of `reference` with vertex i of `test` (for example a
// decoded semi-regular mesh against its original). `peak` is usually the
// bounding-box diagonal of the reference. Errors: sizes differ, no vertices,
// a non-finite coordinate, or `peak` not finite and > 0.
Result<VertexErrorStats> VertexError(const std::vector<Vec3>& reference,
                                     const std::vector<Vec3>& test,
                                     double peak);

// Like VertexError, but each reference vertex is compared with its nearest
// test vertex (ties go to the lowest test index): for two meshes holding the
// same vertices in different orders. The sizes may differ; the matching is
// not forced to be one-to-one (see `distinct_matches`). O(n log n) with a
// k-d tree. Errors: either set empty, a non-finite coordinate, or a bad peak.
Result<VertexErrorStats> VertexErrorByNearest(
    const std::vector<Vec3>& reference, const std::vector<Vec3>& test,
    double peak);

struct SurfaceDistanceOptions {
  // Face samples per face of the mesh with more faces; each mesh gets that
  // many face samples in total (spread over its faces by area, at least one
  // per face), plus one sample at every referenced vertex.
  double samples_per_face = 10;
  // Seed of the sample positions (std::mt19937_64).
  uint64_t seed = 1;
  // Lower bound on the number of face samples of each mesh.
  size_t min_samples = 10000;
  // Threads (0: the machine's cores) that build each direction's index and
  // measure its samples; the result is the same for any count.
  int threads = 0;
  // At most this many samples on each mesh (0: no bound): a mesh whose
  // face and vertex samples would exceed it gets exactly this many face
  // samples, spread by area, and no vertex samples, so that the cost of a
  // measurement stops growing with the mesh (RMS and mean from millions of
  // samples move by far less than their differences of interest).
  uint64_t max_samples = 0;
};

// One-sided and symmetric sampled distances, in the units of the meshes.
// "ab" is measured from samples on A to the surface of B, "ba" the reverse.
// Symmetric values are the larger of the two one-sided ones (as the
// Hausdorff distance is; a mesh far from part of the other is penalised
// whichever side it is on).
struct SurfaceDistance {
  double rms_ab = 0, rms_ba = 0, rms = 0;
  double hausdorff_ab = 0, hausdorff_ba = 0, hausdorff = 0;
  double mean_ab = 0, mean_ba = 0, mean = 0;
  // Bounding-box diagonal of A (of all its positions): the scale for the
  // helpers below and the PSNR peak.
  double diagonal = 0;
  size_t samples_a = 0, samples_b = 0;  // points sampled on A and on B

  // `distance` as a fraction of the diagonal (multiply by 100 for %).
  double FractionOfDiagonal(double distance) const {
    return distance / diagonal;
  }
  // PsnrDb(diagonal, distance).
  double PsnrDb(double distance) const;
};

// METRO-style symmetric surface distance: points sampled on A (every vertex
// referenced by a face, plus random points on every face) are projected on
// the triangles of B with a BVH, and vice versa. The sampled Hausdorff
// distances can only underestimate the true ones (by less as the samples
// grow denser); RMS and mean are over the samples, which follow area except
// for the vertex samples. Zero-area faces are allowed
// (they are measured as segments or points). Unreferenced vertices are
// ignored, except that they count for the bounding box of A. Errors: a mesh
// without faces, a face index out of range, a non-finite coordinate, a
// negative or non-finite samples_per_face, or more than 2^31 face samples
// per mesh. Time on one core: igea.ply (270k faces, 5.6 M samples) against
// itself about 2 s; against a copy with edge-length-sized noise about 4 s.
// Far-apart surfaces cost more: every face within reach must be tested.
Result<SurfaceDistance> SymmetricSurfaceDistance(
    const TriMesh& a, const TriMesh& b,
    const SurfaceDistanceOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_METRICS_H_
