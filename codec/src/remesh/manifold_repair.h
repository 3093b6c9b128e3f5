// Manifold repair: turns a cleaned triangle soup into an oriented manifold
// mesh, the form the remesher's simplifier and hierarchy need.
#ifndef MESHWAVE_REMESH_MANIFOLD_REPAIR_H_
#define MESHWAVE_REMESH_MANIFOLD_REPAIR_H_

#include <cstddef>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

// What RepairManifold changed.
struct RepairReport {
  size_t non_manifold_edges = 0;     // edges of more than two faces
  size_t misoriented_edges = 0;      // two faces ran the edge the same way
  size_t reoriented_faces = 0;       // faces turned over to agree
  size_t non_orientable_cuts = 0;    // edges cut to make a component orientable
  size_t non_manifold_vertices = 0;  // vertices split into several
  size_t added_vertices = 0;         // copies made by the splits
  size_t fallback_cuts = 0;          // extra cuts of a second pass (rare)
};

// Makes `mesh` an oriented manifold in place, keeping every face:
// - an edge shared by exactly two faces is glued; of an edge with more,
//   the two faces that run it in opposite directions and continue each
//   other most smoothly are glued, the others cut off (a fin hanging off a
//   surface leaves the surface whole);
// - faces are turned over so that glued neighbours agree, each component
//   keeping the orientation of most of its faces; where a component cannot
//   be oriented (a Möbius band) the conflicting edge is cut;
// - a vertex whose faces form several fans around it becomes one vertex per
//   fan (copies at the same position, appended after the existing ones).
// Precondition (asserted): every face has three distinct corners in range,
// as after CleanMesh. Linear apart from one sort of the 3F half-edges,
// made on `threads` (ParallelSort; the result does not depend on it).
RepairReport RepairManifold(TriMesh& mesh, int threads = 1);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_MANIFOLD_REPAIR_H_
