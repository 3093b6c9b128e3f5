#include "remesh/remesh_quality.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <numbers>

#include "core/parallel_for.h"

namespace meshwave::remesh {
namespace {

double Angle(const Vec3& at, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - at, v = c - at;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

Vec3 InputNormalAt(const InputSurface& input, const Vec3& point,
                   uint32_t component, uint32_t hint) {
  const InputSurface::Projection q =
      input.Closest(point, Vec3::Zero(), component, hint);
  return q.found() ? input.FaceNormal(q.face) : Vec3(Vec3::Zero());
}

bool IsFlipped(const InputSurface& input, const Vec3& a, const Vec3& b,
               const Vec3& c, uint32_t component, uint32_t hint) {
  return IsFlipped(input, a, b, c, component, hint,
                   InputNormalAt(input, a, component, hint) +
                       InputNormalAt(input, b, component, hint) +
                       InputNormalAt(input, c, component, hint));
}

bool IsFlipped(const InputSurface& input, const Vec3& a, const Vec3& b,
               const Vec3& c, uint32_t component, uint32_t hint,
               const Vec3& sheet) {
  const Vec3 n = (b - a).cross(c - a);
  const double sheet_length = sheet.norm();
  const double min_dot = kMinSheetCos * sheet_length;
  const Vec3 centroid = (a + b + c) / 3;
  const InputSurface::Projection p =
      input.ClosestWithin(centroid, sheet, min_dot, component, hint);
  if (!p.found() || n.dot(input.FaceNormal(p.face)) >= 0) return false;
  Vec3 mean = input.FaceNormal(p.face);
  for (const Vec3* corner : {&a, &b, &c}) {
    const InputSurface::Projection q = input.ClosestWithin(
        (centroid + *corner) / 2, sheet, min_dot, component, p.face);
    if (q.found()) mean += input.FaceNormal(q.face);
  }
  return n.dot(mean) < 0;
}

QualityFigures MeasureQuality(const TriMesh& mesh,
                              const std::vector<uint32_t>& face_component,
                              const InputSurface& input, int threads) {
  // The input normal at every vertex, looked up once (IsFlipped needs it
  // at the three corners of every face).
  std::vector<uint32_t> vertex_component(mesh.positions.size(), 0);
  std::vector<uint8_t> used(mesh.positions.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    for (uint32_t v : mesh.faces[f]) {
      vertex_component[v] = face_component[f];
      used[v] = 1;
    }
  }
  std::vector<Vec3> corner_normals(mesh.positions.size(), Vec3::Zero());
  ParallelFor(mesh.positions.size(), threads, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      if (!used[v]) continue;
      corner_normals[v] = InputNormalAt(
          input, mesh.positions[v], vertex_component[v], InputSurface::kNoFace);
    }
  });
  std::atomic<size_t> flipped{0}, degenerate{0};
  std::mutex mutex;
  double min_angle = std::numbers::pi;
  ParallelFor(mesh.faces.size(), threads, [&](size_t begin, size_t end) {
    size_t my_flipped = 0, my_degenerate = 0;
    double my_min = std::numbers::pi;
    const uint32_t hint = InputSurface::kNoFace;
    for (size_t f = begin; f < end; ++f) {
      const Face& t = mesh.faces[f];
      const Vec3& a = mesh.positions[mesh.faces[f][0]];
      const Vec3& b = mesh.positions[mesh.faces[f][1]];
      const Vec3& c = mesh.positions[mesh.faces[f][2]];
      if (Compactness(a, b, c) < kDegenerateCompactness) ++my_degenerate;
      my_min =
          std::min({my_min, Angle(a, b, c), Angle(b, c, a), Angle(c, a, b)});
      const Vec3 sheet =
          corner_normals[t[0]] + corner_normals[t[1]] + corner_normals[t[2]];
      if (IsFlipped(input, a, b, c, face_component[f], hint, sheet)) {
        ++my_flipped;
      }
    }
    flipped += my_flipped;
    degenerate += my_degenerate;
    std::lock_guard<std::mutex> lock(mutex);
    min_angle = std::min(min_angle, my_min);
  });
  QualityFigures out;
  out.flipped_faces = flipped;
  out.degenerate_faces = degenerate;
  out.min_angle_degrees =
      mesh.faces.empty() ? 0 : min_angle * 180 / std::numbers::pi;
  return out;
}

}  // namespace meshwave::remesh
