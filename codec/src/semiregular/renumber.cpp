// RenumberBase: the same semi-regular mesh over a reordered base mesh.
#include <algorithm>
#include <string>
#include <utility>

#include "meshwave/semiregular.h"
#include "meshwave/subdivision.h"

namespace meshwave {
namespace {

// The edges of one level by their lower endpoint (compressed rows): a vertex
// has about six, so a lookup scans a few entries. A hash map of the finest
// level's million edges was a sixth of an encode (its allocations and
// misses); the rows take two passes over the edges and no hashing.
class EdgeFinder {
 public:
  EdgeFinder(const std::vector<Edge>& edges, uint32_t vertex_count)
      : begin_(vertex_count + 1, 0), entries_(edges.size()) {
    for (const Edge& e : edges) ++begin_[std::min(e[0], e[1]) + 1];
    for (uint32_t v = 0; v < vertex_count; ++v) begin_[v + 1] += begin_[v];
    std::vector<uint32_t> fill(begin_.begin(), begin_.end() - 1);
    for (uint32_t k = 0; k < edges.size(); ++k) {
      const Edge& e = edges[k];
      entries_[fill[std::min(e[0], e[1])]++] = {std::max(e[0], e[1]), k};
    }
  }
  // The index of edge {a, b}, or kNotFound.
  uint32_t Find(uint32_t a, uint32_t b) const {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    if (lo + 1 >= begin_.size()) return kNotFound;
    for (uint32_t n = begin_[lo]; n < begin_[lo + 1]; ++n) {
      if (entries_[n].first == hi) return entries_[n].second;
    }
    return kNotFound;
  }
  static constexpr uint32_t kNotFound = ~uint32_t{0};

 private:
  std::vector<uint32_t> begin_;
  std::vector<std::pair<uint32_t, uint32_t>>
      entries_;  // (higher endpoint, edge)
};

}  // namespace

Result<SemiRegularMesh> RenumberBase(const SemiRegularMesh& mesh,
                                     const std::vector<uint32_t>& new_of_old,
                                     std::vector<Face> new_base_faces,
                                     std::vector<uint32_t>* old_of_new_out) {
  const SemiRegularHierarchy& old = *mesh.hierarchy;
  const uint32_t v0 = old.vertex_count(0);
  if (new_of_old.size() != v0 || new_base_faces.size() != old.faces(0).size()) {
    return InvalidArgument("renumbering does not match the base mesh's size");
  }
  MW_ASSIGN_OR_RETURN(
      auto fresh,
      SemiRegularHierarchy::Build(v0, std::move(new_base_faces), old.levels()));
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
    const EdgeFinder old_edge(old.edges(j), old.vertex_count(j));
    for (uint32_t k = 0; k < fresh->subband_size(j); ++k) {
      const Edge& e = fresh->edges(j)[k];
      const uint32_t found = old_edge.Find(old_of_new[e[0]], old_of_new[e[1]]);
      if (found == EdgeFinder::kNotFound) {
        return InvalidArgument(
            "reordered base faces are not the same mesh (level " +
            std::to_string(j) + ")");
      }
      old_of_new[fresh->vertex_count(j) + k] = old.vertex_count(j) + found;
    }
  }
  SemiRegularMesh out;
  out.hierarchy = std::move(fresh);
  out.positions.resize(old_of_new.size());
  for (size_t v = 0; v < old_of_new.size(); ++v) {
    out.positions[v] = mesh.positions[old_of_new[v]];
  }
  if (old_of_new_out != nullptr) *old_of_new_out = std::move(old_of_new);
  return out;
}

}  // namespace meshwave
