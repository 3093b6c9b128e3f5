// Ordered one-rings of an oriented manifold triangle mesh: for every vertex
// its neighbours in counter-clockwise order. Building them is also the
// manifoldness check the hierarchy code relies on.
#ifndef MESHWAVE_SEMIREGULAR_VERTEX_RINGS_H_
#define MESHWAVE_SEMIREGULAR_VERTEX_RINGS_H_

#include <cstdint>
#include <span>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

class VertexRings {
 public:
  // Fails with kNotManifold naming the first vertex or edge at fault: an
  // edge used twice in the same direction (more than two faces, or faces
  // oriented inconsistently), or a vertex whose faces form several fans.
  // Fails with kInvalidArgument on an index >= vertex_count, on an
  // unreferenced vertex, or on a face with a repeated corner.
  static Result<VertexRings> Build(uint32_t vertex_count,
                                   std::span<const Face> faces);

  // Neighbours of v in counter-clockwise order. For a boundary vertex the
  // ring starts and ends at its two boundary neighbours (ring.front() is the
  // neighbour across the boundary edge that has v's faces on its left).
  std::span<const uint32_t> Ring(uint32_t v) const {
    return {neighbours_.data() + offsets_[v], offsets_[v + 1] - offsets_[v]};
  }
  bool IsBoundary(uint32_t v) const { return boundary_[v] != 0; }
  uint32_t Valence(uint32_t v) const { return offsets_[v + 1] - offsets_[v]; }
  uint32_t vertex_count() const {
    return static_cast<uint32_t>(offsets_.size() - 1);
  }

 private:
  std::vector<uint32_t> offsets_;
  std::vector<uint32_t> neighbours_;
  std::vector<uint8_t> boundary_;
};

}  // namespace meshwave

#endif  // MESHWAVE_SEMIREGULAR_VERTEX_RINGS_H_
