// Checks of a remeshed surface against its input: folded faces (normal
// opposing the input's) and degenerate ones.
#ifndef MESHWAVE_REMESH_REMESH_QUALITY_H_
#define MESHWAVE_REMESH_REMESH_QUALITY_H_

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

// Compactness (4√3·area / Σ edge², 1 for equilateral) below which a face
// counts as degenerate: a smallest angle of about 0.005°.
inline constexpr double kDegenerateCompactness = 1e-4;

// A face is flipped when its normal has a negative dot product with the
// normal of the input face closest to its centroid, among the faces of the
// input component it approximates (face_component[f]; where components
// touch, the nearest face of another one says nothing about orientation).
// Faces must index `mesh`.
QualityFigures MeasureQuality(const TriMesh& mesh,
                              const std::vector<uint32_t>& face_component,
                              const InputSurface& input, int threads);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_REMESH_QUALITY_H_
