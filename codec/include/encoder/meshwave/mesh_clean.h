// Cleaning a mesh read from a file: merged duplicate vertices, dropped
// degenerate and duplicate faces and unreferenced vertices.
#ifndef MESHWAVE_MESH_CLEAN_H_
#define MESHWAVE_MESH_CLEAN_H_

#include <cstddef>

#include "meshwave/mesh.h"

namespace meshwave {

struct CleanOptions {
  bool merge_duplicate_vertices = true;   // bit-identical positions
  bool drop_degenerate_faces = true;      // a repeated corner index
  bool drop_duplicate_faces = true;       // same three vertices, any order
  bool drop_unreferenced_vertices = true;
};

// What cleaning changed, and what it found but left alone.
struct CleanReport {
  size_t merged_vertices = 0;
  size_t degenerate_faces = 0;
  size_t duplicate_faces = 0;
  size_t unreferenced_vertices = 0;
  size_t zero_area_faces = 0;  // distinct corners but no area; kept
};

// Cleans in place. Vertex order is kept (stable compaction); of merged
// vertices and duplicate faces the first one stays. Merged duplicates are
// always removed; `unreferenced_vertices` counts the others whether or not
// they are dropped. Faces must index existing vertices.
CleanReport CleanMesh(TriMesh& mesh, const CleanOptions& options = {});

}  // namespace meshwave

#endif  // MESHWAVE_MESH_CLEAN_H_
