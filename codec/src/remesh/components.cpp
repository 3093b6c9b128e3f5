#include "remesh/components.h"

#include "remesh/union_find.h"

namespace meshwave::remesh {

Components LabelComponents(const TriMesh& mesh) {
  UnionFind sets(mesh.positions.size());
  for (const Face& f : mesh.faces) {
    sets.Union(f[0], f[1]);
    sets.Union(f[1], f[2]);
  }
  Components out;
  std::vector<uint32_t> id_of_root(mesh.positions.size(), Components::kNone);
  out.of_face.resize(mesh.faces.size());
  out.of_vertex.assign(mesh.positions.size(), Components::kNone);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const uint32_t root = sets.Find(mesh.faces[f][0]);
    if (id_of_root[root] == Components::kNone) id_of_root[root] = out.count++;
    out.of_face[f] = id_of_root[root];
    for (uint32_t v : mesh.faces[f]) out.of_vertex[v] = out.of_face[f];
  }
  return out;
}

}  // namespace meshwave::remesh
