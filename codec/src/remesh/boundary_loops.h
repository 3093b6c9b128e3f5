// The boundary loops of an oriented manifold mesh, parametrised by arc
// length, so the remesher can place boundary vertices exactly on the input
// boundary and space them evenly along it.
#ifndef MESHWAVE_REMESH_BOUNDARY_LOOPS_H_
#define MESHWAVE_REMESH_BOUNDARY_LOOPS_H_

#include <cstdint>
#include <vector>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

class BoundaryLoops {
 public:
  static constexpr uint32_t kNone = 0xffffffffu;

  // `mesh` must be an oriented manifold (as after RepairManifold). A loop
  // runs in the direction its edges have in their faces. Keeps a pointer
  // to mesh.positions: the mesh must outlive this object.
  explicit BoundaryLoops(const TriMesh& mesh);

  size_t count() const { return lengths_.size(); }
  double Length(uint32_t loop) const { return lengths_[loop]; }

  struct Location {
    uint32_t loop = kNone;  // kNone: not a boundary vertex
    double s = 0;           // arc length from the loop's first vertex
  };
  Location Locate(uint32_t vertex) const;

  struct Point {
    Vec3 position = Vec3::Zero();
    uint32_t face = kNone;  // the face of the boundary edge it lies on
  };
  // The point at arc length s (taken modulo the loop's length).
  Point At(uint32_t loop, double s) const;

  // The arc length halfway from a to b going forward along the loop.
  double Midway(uint32_t loop, double a, double b) const;

 private:
  std::vector<uint32_t>
      offsets_;  // loop l: entries [offsets_[l], offsets_[l+1])
  std::vector<uint32_t> vertices_;  // in loop order
  std::vector<uint32_t> faces_;     // face of the edge vertices_[i] -> next
  std::vector<double> arc_;         // arc length at vertices_[i]
  std::vector<double> lengths_;
  std::vector<uint32_t> entry_of_vertex_;  // index into vertices_, or kNone
  const std::vector<Vec3>* positions_;
};

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_BOUNDARY_LOOPS_H_
