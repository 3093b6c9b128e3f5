// Edge flips on a simplified base mesh: quadric simplification leaves caps
// (a corner near 180°), and a cap's corner children fold once subdivision
// moves the new vertices onto a curved surface.
#ifndef MESHWAVE_REMESH_BASE_FLIPS_H_
#define MESHWAVE_REMESH_BASE_FLIPS_H_

#include <cstddef>

#include "meshwave/mesh.h"

namespace meshwave::remesh {

// Flips inner edges of an oriented manifold mesh while that raises the
// smallest angle of the two faces beside the edge by at least a degree
// (the Delaunay criterion, made robust), as long as the new faces do not
// turn against the old ones (dot product of normals above 0.5) and the
// topology is kept (the new edge must not exist yet; every vertex keeps at
// least three faces). Vertices do not move. Returns the number of flips.
size_t FlipToImproveAngles(TriMesh& mesh);

}  // namespace meshwave::remesh

#endif  // MESHWAVE_REMESH_BASE_FLIPS_H_
