// Welding: merges vertices whose coordinates are bit-identical (the first
// occurrence stays, the order of first occurrences is kept) and remaps the
// faces, as CleanMesh merges duplicates. By sorting, not hashing: positions
// come from untrusted files, and a fixed hash can be flooded with colliding
// keys.
#ifndef MESHWAVE_ASSET_WELD_H_
#define MESHWAVE_ASSET_WELD_H_

#include <cstddef>

#include "meshwave/mesh.h"

namespace meshwave {

// Welds `mesh` in place; faces must index existing positions. Returns the
// number of positions merged away.
size_t WeldPositions(TriMesh& mesh);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_WELD_H_
