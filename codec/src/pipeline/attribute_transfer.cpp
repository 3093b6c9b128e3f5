#include "meshwave/attribute_transfer.h"

#include "pipeline/color_transfer.h"

namespace meshwave {

Result<VertexAttributes> TransferAttributes(const MeshAsset& asset, const SemiRegularMesh& mesh,
                                            int threads) {
  VertexAttributes out;
  if (!asset.color.empty()) {
    MW_ASSIGN_OR_RETURN(out.colors, TransferCornerColors(asset.mesh.positions, asset.mesh.faces,
                                                         asset.color, mesh.positions, threads));
  }
  return out;
}

}  // namespace meshwave
