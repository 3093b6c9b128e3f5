// Connected components of a triangle mesh (faces joined through shared
// vertices), numbered in the order of their first face.
#ifndef MESHWAVE_REMESH_COMPONENTS_H_
#define MESHWAVE_REMESH_COMPONENTS_H_

#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

struct Components {
  static constexpr uint32_t kNone = 0xffffffffu;
  uint32_t count = 0;
  std::vector<uint32_t> of_face;    // component of each face
  std::vector<uint32_t> of_vertex;  // kNone for unreferenced vertices
};

// Faces must index existing vertices.
Components LabelComponents(const TriMesh& mesh);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_COMPONENTS_H_
