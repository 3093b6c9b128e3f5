// Quadric-error edge-collapse simplification (Garland-Heckbert) down to a
// coarse base mesh with the topology and the boundaries of its input.
#ifndef MESHWAVE_REMESH_QEM_SIMPLIFIER_H_
#define MESHWAVE_REMESH_QEM_SIMPLIFIER_H_

#include <cstdint>
#include <functional>
#include <vector>

#include "meshwave/mesh.h"
#include "remesh/components.h"

namespace meshwave::remesh {

struct SimplifyOptions {
  // Faces to stop at, per component (indexed like Components); a component
  // at or below its target is left alone. A collapse removes two faces (one
  // on a boundary), so a component may end one face below its target.
  std::vector<uint32_t> target_faces;
  // Called now and then with the fraction of the planned collapses done.
  std::function<void(double fraction)> progress;
};

struct SimplifiedMesh {
  static constexpr uint32_t kNone = 0xffffffffu;
  TriMesh mesh;  // oriented manifold, every vertex used, input orientation
  // Per vertex of `mesh`: the input vertex whose position it kept, or kNone
  // when it moved to the quadric's optimal point. Boundary vertices always
  // keep an input boundary vertex's position.
  std::vector<uint32_t> source_vertex;
  std::vector<uint32_t> component;  // per vertex, as in the input
  size_t collapses = 0;
};

// Simplifies an oriented manifold mesh (as RepairManifold leaves it) by
// collapsing the edge of least quadric error (area-weighted face planes plus
// planes perpendicular to boundary edges) plus a small edge-length term that
// keeps flat regions evenly sized. A collapse is refused when it would
// - change the topology: the link condition (the common neighbours of the
//   two ends are exactly the apexes of the edge's faces), an inner edge
//   joining two boundary vertices, a vertex left with fewer than three
//   faces (one on a boundary), a component below its target;
// - fold a face (its normal turning by more than about 75°) or make the
//   worst triangle around it both bad (compactness < 0.05) and worse.
// Boundary vertices stay input boundary vertices (an edge touching the
// boundary collapses onto its boundary end), so the base boundary is a
// subset of the input's boundary loops. Runs in O(F log F).
SimplifiedMesh SimplifyByEdgeCollapse(const TriMesh& mesh,
                                      const Components& components,
                                      const SimplifyOptions& options);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_QEM_SIMPLIFIER_H_
