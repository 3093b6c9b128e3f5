// RenumberBase: the same semi-regular mesh over a reordered base mesh.
#include <string>
#include <unordered_map>

#include "core/edge_key.h"
#include "meshwave/semiregular.h"

namespace meshwave {
namespace {

}  // namespace

Result<SemiRegularMesh> RenumberBase(const SemiRegularMesh& mesh,
                                     const std::vector<uint32_t>& new_of_old,
                                     std::vector<Face> new_base_faces) {
  const SemiRegularHierarchy& old = *mesh.hierarchy;
  const uint32_t v0 = old.vertex_count(0);
  if (new_of_old.size() != v0 || new_base_faces.size() != old.faces(0).size()) {
    return InvalidArgument("renumbering does not match the base mesh's size");
  }
  MW_ASSIGN_OR_RETURN(auto fresh, SemiRegularHierarchy::Build(
                                      v0, std::move(new_base_faces), old.levels()));
  // old_of_new[v] for every vertex of the new hierarchy, level by level.
  std::vector<uint32_t> old_of_new(fresh->vertex_count(fresh->levels()));
  std::vector<char> seen(v0, 0);
  for (uint32_t v = 0; v < v0; ++v) {
    if (new_of_old[v] >= v0 || seen[new_of_old[v]]) {
      return InvalidArgument("base renumbering is not a permutation");
    }
    seen[new_of_old[v]] = 1;
    old_of_new[new_of_old[v]] = v;
  }
  for (int j = 0; j < old.levels(); ++j) {
    std::unordered_map<uint64_t, uint32_t> old_edge;
    old_edge.reserve(old.subband_size(j));
    for (uint32_t k = 0; k < old.subband_size(j); ++k) {
      old_edge.emplace(EdgeKey(old.edges(j)[k][0], old.edges(j)[k][1]), k);
    }
    for (uint32_t k = 0; k < fresh->subband_size(j); ++k) {
      const Edge& e = fresh->edges(j)[k];
      auto it = old_edge.find(EdgeKey(old_of_new[e[0]], old_of_new[e[1]]));
      if (it == old_edge.end()) {
        return InvalidArgument("reordered base faces are not the same mesh (level " +
                               std::to_string(j) + ")");
      }
      old_of_new[fresh->vertex_count(j) + k] = old.vertex_count(j) + it->second;
    }
  }
  SemiRegularMesh out;
  out.hierarchy = std::move(fresh);
  out.positions.resize(old_of_new.size());
  for (size_t v = 0; v < old_of_new.size(); ++v) {
    out.positions[v] = mesh.positions[old_of_new[v]];
  }
  return out;
}

}  // namespace meshwave
