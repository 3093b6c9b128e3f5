// VertexError and VertexErrorByNearest (meshwave/metrics.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "meshwave/metrics.h"
#include "metrics/input_checks.h"
#include "metrics/point_kdtree.h"

namespace meshwave {
namespace {

// Sums distances in vertex order, so results do not depend on threading or
// on the order matches were found in.
class ErrorAccumulator {
 public:
  void Add(double distance_squared) {
    const double d = std::sqrt(distance_squared);
    sum_ += d;
    sum_squared_ += distance_squared;
    max_ = std::max(max_, d);
    ++count_;
  }

  VertexErrorStats Finish(double peak, bool by_nearest,
                          size_t distinct_matches) const {
    VertexErrorStats stats;
    const auto n = static_cast<double>(count_);
    stats.rms = std::sqrt(sum_squared_ / n);
    stats.max = max_;
    stats.mean = sum_ / n;
    stats.psnr_db = PsnrDb(peak, stats.rms);
    stats.peak = peak;
    stats.count = count_;
    stats.matched_by_nearest = by_nearest;
    stats.distinct_matches = distinct_matches;
    return stats;
  }

 private:
  double sum_ = 0;
  double sum_squared_ = 0;
  double max_ = 0;
  size_t count_ = 0;
};

Status CheckVertexSets(const std::vector<Vec3>& reference,
                       const std::vector<Vec3>& test, double peak) {
  if (reference.empty() || test.empty()) {
    return InvalidArgument(
        std::string("vertex error needs vertices, but the ") +
        (reference.empty() ? "reference" : "test") + " set is empty");
  }
  if (reference.size() >= std::numeric_limits<uint32_t>::max() ||
      test.size() >= std::numeric_limits<uint32_t>::max()) {
    return InvalidArgument("vertex error: more than 2^32 - 2 vertices");
  }
  MW_RETURN_IF_ERROR(metrics::CheckFinite(reference, "reference vertices"));
  MW_RETURN_IF_ERROR(metrics::CheckFinite(test, "test vertices"));
  return metrics::CheckPeak(peak);
}

}  // namespace

double PsnrDb(double peak, double rms) {
  if (rms == 0) return std::numeric_limits<double>::infinity();
  return 20.0 * std::log10(peak / rms);
}

Result<VertexErrorStats> VertexError(const std::vector<Vec3>& reference,
                                     const std::vector<Vec3>& test,
                                     double peak) {
  if (reference.size() != test.size()) {
    return InvalidArgument(
        "same-index vertex error needs equal vertex counts, got " +
        std::to_string(reference.size()) + " and " +
        std::to_string(test.size()));
  }
  MW_RETURN_IF_ERROR(CheckVertexSets(reference, test, peak));
  ErrorAccumulator accumulator;
  for (size_t i = 0; i < reference.size(); ++i) {
    accumulator.Add((reference[i] - test[i]).squaredNorm());
  }
  return accumulator.Finish(peak, /*by_nearest=*/false, reference.size());
}

Result<VertexErrorStats> VertexErrorByNearest(
    const std::vector<Vec3>& reference, const std::vector<Vec3>& test,
    double peak) {
  MW_RETURN_IF_ERROR(CheckVertexSets(reference, test, peak));
  const metrics::PointKdTree tree(test);
  std::vector<bool> used(test.size(), false);
  size_t distinct = 0;
  ErrorAccumulator accumulator;
  for (const Vec3& v : reference) {
    const metrics::PointKdTree::Nearest nearest = tree.FindNearest(v);
    accumulator.Add(nearest.distance_squared);
    if (!used[nearest.index]) {
      used[nearest.index] = true;
      ++distinct;
    }
  }
  return accumulator.Finish(peak, /*by_nearest=*/true, distinct);
}

}  // namespace meshwave
