#include "meshwave/fidelity.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "meshwave/metrics.h"
#include "meshwave/progressive_decoder.h"

namespace meshwave {
namespace {

// Surface PSNR gained per doubling of the finest level's vertices, measured
// on the bunny's remeshes (35 k, 77 k, 140 k vertices: 76.6, 81.0, 85.4
// dB): the guess for the second attempt. Later attempts use the slope
// measured between the attempts around the target (fandisk's is steeper:
// its sharp edges need the density more).
constexpr double kDbPerDoubling = 4.5;
// Attempts aim this far above the target (the guess is rough), and stop
// when one lands within kSlackDb above it: denser would cost bytes for
// fidelity nobody asked for.
constexpr double kAimAboveDb = 0.5;
constexpr double kSlackDb = 2;
constexpr int kMaxAttempts = 6;
constexpr int kMaxRemeshLevels = 8;  // RemeshOptions::levels' range
// Fidelity is measured on at most this many samples per mesh: on every
// shared mesh (270 k faces at most) all of them, and on a 10 M-triangle
// scan a fixed cost instead of minutes; the RMS of 4 M samples is within
// a few thousandths of a dB of the RMS of all.
constexpr uint64_t kFidelitySamples = 4'000'000;

Result<double> RemeshPsnr(const TriMesh& input, const SemiRegularMesh& remesh, int threads) {
  SurfaceDistanceOptions options;
  options.threads = threads;
  options.samples_per_face = 2;  // as `meshwave remesh` measures: fast on 1 M faces
  options.max_samples = kFidelitySamples;
  MW_ASSIGN_OR_RETURN(SurfaceDistance d, SymmetricSurfaceDistance(input, remesh.Finest(), options));
  return d.PsnrDb(d.rms);
}

struct Attempt {
  double log2_ratio = 0;  // finest vertices per input vertex, log2
  double psnr_db = 0;
  RemeshResult result;
};

}  // namespace

Result<FidelityRemesh> RemeshToFidelity(const TriMesh& input, RemeshOptions options,
                                        double fidelity_db, double max_vertex_ratio) {
  int attempts = 0;
  double input_vertices = 1;
  size_t base_per_ratio = 1;  // base faces asked per unit of ratio (first attempt's)
  int first_levels = 0;
  // Levels the caller fixed (`--levels J`) stay: the density then comes
  // from the base alone.
  const bool levels_fixed = options.levels > 0;
  // The densest attempt still short of the fidelity and the sparsest that
  // reaches it: the two the next guess interpolates between.
  std::optional<Attempt> below, above;
  auto run = [&](double log2_ratio) -> Status {
    if (attempts > 0) {
      // Density from levels first: each level is four times the vertices
      // over the same base, and a small base with more levels codes every
      // prefix in fewer bytes than a large base (the bunny at 3.4 times its
      // vertices: 4 levels over 930 base faces beat 3 levels over 3,703 at
      // every budget from 5 to 150 KB, by 2.1 to 3.1 dB from 16 KB on).
      // But a base much smaller than the default fits the surface worse
      // (the elephant sample at twice its vertices as 4 levels over half
      // the base came out below its 3-level default): the base takes the
      // rest, from 0.76 to 3 times the first one's.
      const int extra =
          levels_fixed ? 0
                       : std::clamp(static_cast<int>(std::floor(log2_ratio / 2 + 0.2)), 0,
                                    kMaxRemeshLevels - first_levels);
      options.levels = first_levels + extra;
      const double base =
          static_cast<double>(base_per_ratio) * std::exp2(log2_ratio - 2.0 * extra);
      options.base_faces = static_cast<int>(std::lround(std::clamp(base, 1.0, 1e9)));
    }
    Attempt a;
    MW_ASSIGN_OR_RETURN(a.result, Remesh(input, options));
    ++attempts;
    MW_ASSIGN_OR_RETURN(a.psnr_db, RemeshPsnr(input, a.result.mesh, options.threads));
    if (attempts == 1) {
      input_vertices = static_cast<double>(std::max<size_t>(a.result.input_vertices, 1));
      const double ratio = static_cast<double>(a.result.finest_vertices) / input_vertices;
      base_per_ratio = static_cast<size_t>(
          std::max(1.0, static_cast<double>(a.result.target_base_faces) / ratio));
      first_levels = a.result.levels;
    }
    a.log2_ratio = std::log2(static_cast<double>(a.result.finest_vertices) / input_vertices);
    if (a.psnr_db >= fidelity_db) {
      if (!above || a.log2_ratio < above->log2_ratio) above = std::move(a);
    } else if (!below || a.psnr_db > below->psnr_db) {
      below = std::move(a);
    }
    return Status::Ok();
  };
  MW_RETURN_IF_ERROR(run(0));
  const double max_log2 = std::log2(max_vertex_ratio);
  while (attempts < kMaxAttempts) {
    if (above && (!below || above->psnr_db <= fidelity_db + kSlackDb)) break;
    const double aim = fidelity_db + kAimAboveDb;
    double next;
    if (above) {  // between the two: the secant through them
      const double slope = (above->psnr_db - below->psnr_db) /
                           std::max(above->log2_ratio - below->log2_ratio, 1e-6);
      next = below->log2_ratio + (aim - below->psnr_db) / std::max(slope, 1e-6);
      // PSNR is far from linear in log density (fandisk: 78.7 dB at 7.8x,
      // 81.4 at 10.9x, 91.2 at 16x): stay in the middle half of the
      // interval, so that it shrinks by a quarter at least.
      const double width = above->log2_ratio - below->log2_ratio;
      next = std::clamp(next, below->log2_ratio + 0.25 * width, above->log2_ratio - 0.25 * width);
    } else {  // all short: the guessed slope, from the densest so far
      if (below->log2_ratio >= max_log2 - 0.07) break;  // at the limit already
      next = below->log2_ratio + (aim - below->psnr_db) / kDbPerDoubling;
    }
    next = std::min(next, max_log2);
    const double lo = below ? below->log2_ratio : 0;
    const double hi = above ? above->log2_ratio : max_log2 + 1;
    if (next <= lo + 0.05 || next >= hi - 0.05) break;  // nothing left between them
    MW_RETURN_IF_ERROR(run(next));
  }
  FidelityRemesh out;
  out.attempts = attempts;
  Attempt& kept = above ? *above : *below;
  out.psnr_db = kept.psnr_db;
  out.result = std::move(kept.result);
  return out;
}

int PrecisionForFidelity(double fidelity_db) {
  // Measured on data/holes.off (semi-regular, no remesh error): complete
  // streams at precision 10, 12, 14, 16, 18 reach 73.8, 84.7, 95.7, 107.8,
  // 121.0 dB.
  constexpr double kDbPerBit = 6.02;
  constexpr double kDbAtZero = 12;
  constexpr double kHeadroomDb = 10;
  const double bits = (fidelity_db + kHeadroomDb - kDbAtZero) / kDbPerBit;
  return std::clamp(static_cast<int>(std::ceil(bits)), EncodeOptions{}.precision, 30);
}

Result<double> CompleteStreamPsnr(const TriMesh& original, const EncodedStream& stream,
                                  int threads) {
  MW_ASSIGN_OR_RETURN(auto decoder, ProgressiveDecoder::Create(stream.header));
  for (uint32_t id = 0; id < stream.packets.size(); ++id) {
    MW_RETURN_IF_ERROR(decoder->AddPacket(id, stream.packets[id]));
  }
  SurfaceDistanceOptions options;
  options.threads = threads;
  options.max_samples = kFidelitySamples;
  MW_ASSIGN_OR_RETURN(SurfaceDistance d,
                      SymmetricSurfaceDistance(original,
                                               decoder->OriginalReady() ? decoder->OriginalMesh()
                                                                        : decoder->Mesh(),
                                               options));
  return d.PsnrDb(d.rms);
}

}  // namespace meshwave
