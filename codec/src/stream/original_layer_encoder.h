// The encoding side of the original layer (docs/FORMAT.md 2.5): the
// user's mesh as read, its connectivity and its positions on a grid of
// step diagonal x 2^-precision, as packets that follow the semi-regular
// stream.
#ifndef MESHWAVE_STREAM_ORIGINAL_LAYER_ENCODER_H_
#define MESHWAVE_STREAM_ORIGINAL_LAYER_ENCODER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "stream.pb.h"

namespace meshwave::original {

struct EncodedLayer {
  proto::Original header;
  // The connectivity, the coarse positions, then each refinement plane.
  std::vector<std::string> packets;
  // The layer's distortion chain (FORMAT.md 2.1), counted as the remesh's
  // chains count (squared vertex errors summed over `remesh_vertices`):
  // before any of it, the remesh's error against the original; per
  // packet, what it takes off.
  double chain_start = 0;
  std::vector<double> reduction;
};

// `original` as read (any faces the readers accept); `remesh_psnr_db`: the
// symmetric surface PSNR of the remesh the stream ends in against the
// original, peak its bounding-box diagonal (0 when unknown or exact), which
// the coarse positions must beat.
// refinement_planes -1: the most that keep the coarse positions' error
// below the remesh's (at most kMaxOriginalRefinementPlanes). Errors: an
// empty mesh, a non-finite coordinate, a precision outside [4, 29].
Result<EncodedLayer> EncodeLayer(const TriMesh& original, double remesh_psnr_db,
                                 uint64_t remesh_vertices, int precision, int refinement_planes);

}  // namespace meshwave::original

#endif  // MESHWAVE_STREAM_ORIGINAL_LAYER_ENCODER_H_
