// Attributes of an input asset onto the semi-regular mesh that encodes it:
// each channel's values at the mesh's vertices, sampled from the original
// surface, for EncodeMesh (meshwave/encoder.h).
#ifndef MESHWAVE_ATTRIBUTE_TRANSFER_H_
#define MESHWAVE_ATTRIBUTE_TRANSFER_H_

#include "meshwave/encoder.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/semiregular.h"
#include "meshwave/status.h"

namespace meshwave {

// For each vertex of `mesh` (finest level, in its order), the asset's
// vertex colour at the nearest point of its surface, interpolated from
// that face's corner colours (linear RGB; alpha is not carried). Empty
// attributes when the asset has no colours. kInvalidArgument when its
// colours do not fit its faces (a reader's output always does).
// `threads` as ResolveThreads takes them; the result does not depend on it.
Result<VertexAttributes> TransferAttributes(const MeshAsset& asset, const SemiRegularMesh& mesh,
                                            int threads = 0);

}  // namespace meshwave

#endif  // MESHWAVE_ATTRIBUTE_TRANSFER_H_
