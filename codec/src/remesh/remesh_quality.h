// Checks of a remeshed surface against its input: folded faces (normal
// opposing the input's) and degenerate ones.
#ifndef MESHWAVE_REMESH_REMESH_QUALITY_H_
#define MESHWAVE_REMESH_REMESH_QUALITY_H_

#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"
#include "remesh/input_surface.h"

namespace meshwave::remesh {

struct QualityFigures {
  size_t flipped_faces = 0;
  size_t degenerate_faces = 0;
  double min_angle_degrees = 0;  // smallest angle of any face
};

// Compactness of a triangle: 4√3·area / Σ edge², 1 for an equilateral
// triangle, 0 without area.
inline double Compactness(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double sum =
      (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(sum > 0)) return 0;
  return 2 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / sum;
}

// Compactness below which a face counts as degenerate: a smallest angle of
// about 0.005°.
inline constexpr double kDegenerateCompactness = 1e-4;

// IsFlipped looks inside a face only at input faces whose normal makes at
// most ~120° with its corners' sheet: the back of a thin part is at ~180°,
// the other slope of a crease (which counts) well within 120°.
inline constexpr double kMinSheetCos = -0.5;

// Whether triangle (a, b, c) is turned against the input surface of
// `component` under it: its normal has a negative dot product with the
// input normal at the point closest to its centroid, and also with the mean
// of the input normals at the points closest to the centroid and to the
// three points halfway from it to the corners (a small face across a sharp
// ridge can be past perpendicular to the nearest face at its centroid
// without being turned over). Only faces of `component` count: where
// components touch, another one's nearest face says nothing.
//
// "Under it" means on the sheet its corners lie on: the points inside the
// face are looked up only among input faces turned less than ~120° from
// the sum of the input normals at its three corners. Inside a part thinner
// than the face's sag (a chord across a curved flap 0.04 units thick, with
// edges of 0.08) the point nearest to the centroid is on the back sheet,
// whose normal opposes the front's and says nothing about a face whose
// corners all lie on the front; the unrestricted test counted such faces
// as flipped. A face that really is turned over is still caught: its own
// corners' input normals oppose it, and so does the sheet they define
// (the restriction follows the corners, never the face's own normal).
// `hint` as in TriangleBvh::ClosestPoint.
bool IsFlipped(const InputSurface& input, const Vec3& a, const Vec3& b,
               const Vec3& c, uint32_t component, uint32_t hint);
// The same with the corners' sheet given: the sum of InputNormalAt at the
// three corners (MeasureQuality looks each vertex up once).
bool IsFlipped(const InputSurface& input, const Vec3& a, const Vec3& b,
               const Vec3& c, uint32_t component, uint32_t hint,
               const Vec3& sheet);

// Unit normal of the input face of `component` closest to `point` (zero
// if the component has none).
Vec3 InputNormalAt(const InputSurface& input, const Vec3& point,
                   uint32_t component, uint32_t hint);

// Flipped faces (IsFlipped, face f approximating input component
// face_component[f]), degenerate faces and the smallest angle. Faces must
// index `mesh`.
QualityFigures MeasureQuality(const TriMesh& mesh,
                              const std::vector<uint32_t>& face_component,
                              const InputSurface& input, int threads);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_REMESH_QUALITY_H_
