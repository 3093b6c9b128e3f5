#include "stream/original_layer_decoder.h"

#include <string>

#include "original/original_connectivity.h"

namespace meshwave::original {

Status LayerDecoder::Add(int part, std::string_view payload) {
  if (part == 0) {
    MW_ASSIGN_OR_RETURN(Traversal traversal,
                        DecodeConnectivity(payload, layer_.vertex_count, layer_.face_count));
    positions_.reset();
    traversal_ = std::move(traversal);
    positions_.emplace(*traversal_, static_cast<int>(layer_.refinement_planes), layer_.extent);
    return Status::Ok();
  }
  if (!positions_) return InvalidArgument("original layer: positions before the connectivity");
  return positions_->Add(part - 1, payload);
}

TriMesh LayerDecoder::Mesh() const {
  TriMesh mesh;
  if (!ready()) return mesh;
  const std::vector<std::array<double, 3>> grid = positions_->GridPositions();
  mesh.positions.reserve(grid.size());
  for (const std::array<double, 3>& q : grid) {
    mesh.positions.emplace_back(layer_.origin[0] + q[0] * layer_.step,
                                layer_.origin[1] + q[1] * layer_.step,
                                layer_.origin[2] + q[2] * layer_.step);
  }
  mesh.faces = traversal_->faces;
  return mesh;
}

}  // namespace meshwave::original
