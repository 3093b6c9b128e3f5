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
  // Stop once the whole mesh has at most this many faces. The cheapest
  // collapse anywhere goes first, so components share the faces by how
  // much error their simplification costs, not by size.
  size_t target_faces = 0;
  // Faces each component keeps at least (indexed like Components; empty:
  // no floor beyond what topology needs). A collapse removes two faces
  // (one on a boundary), so a component may end one face below its floor.
  std::vector<uint32_t> min_faces;
  // Collapses that the simplifier puts off (they make a sliver, a valence-3
  // vertex, a face spanning a bend of more than 90°, or an edge longer than
  // max_edge_length) are made only once
  // nothing else is left, and only in components above this many faces
  // (indexed like Components; empty: everywhere). The remesher passes each
  // component's share of the target by area, so parts that cannot shrink
  // cleanly (claws, teeth) still shrink to their share, while no part is
  // forced below its share at the cost of folds.
  std::vector<uint32_t> late_floor;
  // A collapse that makes an edge longer than this is put off too (0: no
  // limit): very large base faces over curved or concave regions (ogre's
  // shoulders) are where projecting new vertices goes wrong.
  double max_edge_length = 0;
  // Input vertices (indexed like the mesh; empty: none) that must survive
  // in the base at their own position: features the remesher found it
  // missed on a first try (the tip of an ear the quadric error let go).
  std::vector<uint8_t> locked;
  // Called now and then with the fraction of the planned collapses done.
  std::function<void(double fraction)> progress;
  // Threads for the set-up (quadrics, the first queue); the collapses run
  // on the calling thread. The result does not depend on it.
  int threads = 1;
  // Other work (may be empty) run on a second thread while the collapses
  // run, once the set-up is done with every thread; with threads == 1 it
  // runs after them. Its exception is rethrown after both have ended.
  std::function<void()> beside;
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
