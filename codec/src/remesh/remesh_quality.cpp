#include "remesh/remesh_quality.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numbers>

#include "remesh/parallel_for.h"

namespace meshwave::remesh {
namespace {

double Angle(const Vec3& at, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - at, v = c - at;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

QualityFigures MeasureQuality(const TriMesh& mesh,
                              const std::vector<uint32_t>& face_component,
                              const InputSurface& input, int threads) {
  std::atomic<size_t> flipped{0}, degenerate{0};
  std::mutex mutex;
  double min_angle = std::numbers::pi;
  ParallelFor(mesh.faces.size(), threads, [&](size_t begin, size_t end) {
    size_t my_flipped = 0, my_degenerate = 0;
    double my_min = std::numbers::pi;
    uint32_t hint = InputSurface::kNoFace;
    for (size_t f = begin; f < end; ++f) {
      const Vec3& a = mesh.positions[mesh.faces[f][0]];
      const Vec3& b = mesh.positions[mesh.faces[f][1]];
      const Vec3& c = mesh.positions[mesh.faces[f][2]];
      const Vec3 n = (b - a).cross(c - a);
      const double sum = (b - a).squaredNorm() + (c - b).squaredNorm() +
                         (a - c).squaredNorm();
      const double compactness = sum > 0 ? 2 * std::sqrt(3.0) * n.norm() / sum : 0;
      if (compactness < kDegenerateCompactness) ++my_degenerate;
      my_min = std::min({my_min, Angle(a, b, c), Angle(b, c, a), Angle(c, a, b)});
      const InputSurface::Projection p = input.Closest(
          (a + b + c) / 3, Vec3::Zero(), face_component[f], hint);
      if (!p.found()) continue;
      hint = p.face;
      if (n.dot(input.FaceNormal(p.face)) < 0) ++my_flipped;
    }
    flipped += my_flipped;
    degenerate += my_degenerate;
    std::lock_guard<std::mutex> lock(mutex);
    min_angle = std::min(min_angle, my_min);
  });
  QualityFigures out;
  out.flipped_faces = flipped;
  out.degenerate_faces = degenerate;
  out.min_angle_degrees = mesh.faces.empty() ? 0 : min_angle * 180 / std::numbers::pi;
  return out;
}

}  // namespace meshwave::remesh
