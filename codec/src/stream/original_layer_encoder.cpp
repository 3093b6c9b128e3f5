#include "stream/original_layer_encoder.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "original/original_connectivity.h"
#include "original/original_positions.h"
#include "stream/stream_format.h"

namespace meshwave::original {

Result<EncodedLayer> EncodeLayer(const TriMesh& original, double remesh_psnr_db,
                                 uint64_t remesh_vertices, int precision, int refinement_planes) {
  const size_t n = original.positions.size();
  if (n == 0) return InvalidArgument("original layer: the mesh has no vertices");
  if (n > kMaxOriginalVertices || original.faces.size() > kMaxOriginalFaces) {
    return InvalidArgument("original layer: the mesh is larger than a stream carries");
  }
  if (precision < 4 || precision > 29) {
    return InvalidArgument("original layer: precision " + std::to_string(precision) +
                           " (4 to 29)");
  }
  Vec3 lo = original.positions[0], hi = lo;
  for (const Vec3& p : original.positions) {
    if (!p.allFinite()) return InvalidArgument("original layer: a coordinate is not finite");
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  // A mesh of one point still needs a step.
  const double step = diagonal > 0 ? std::ldexp(diagonal, -precision) : 1.0;
  std::vector<GridPoint> q(n);
  uint32_t extent = 0;
  for (size_t v = 0; v < n; ++v) {
    for (int a = 0; a < 3; ++a) {
      const double cell = std::round((original.positions[v][a] - lo[a]) / step);
      q[v][a] = static_cast<uint32_t>(std::clamp(cell, 0.0, double{kMaxGridCoordinate}));
      extent = std::max(extent, q[v][a]);
    }
  }

  // The coarse positions must be at least as close to the original as the
  // remesh is: a cell of 2^s steps errs by (2^s step)^2 / 4 per vertex.
  const double remesh_rms = diagonal * std::pow(10.0, -remesh_psnr_db / 20);
  const double remesh_error =
      std::isfinite(remesh_psnr_db) && remesh_psnr_db > 0 ? remesh_rms * remesh_rms : 0.0;
  int planes = refinement_planes;
  if (planes < 0) {
    planes = 0;
    while (planes < static_cast<int>(kMaxOriginalRefinementPlanes) &&
           std::pow(std::ldexp(step, planes + 1), 2) / 4 <= remesh_error) {
      ++planes;
    }
  }
  planes = std::min(planes, static_cast<int>(kMaxOriginalRefinementPlanes));

  EncodedLayer out;
  Traversal traversal;
  MW_ASSIGN_OR_RETURN(std::string connectivity,
                      EncodeConnectivity(static_cast<uint32_t>(n), original.faces, &traversal));
  out.packets.push_back(std::move(connectivity));
  std::vector<std::string> positions = EncodePositions(traversal, q, planes);
  for (std::string& p : positions) out.packets.push_back(std::move(p));

  out.header.set_vertex_count(static_cast<uint32_t>(n));
  out.header.set_face_count(original.faces.size());
  for (int a = 0; a < 3; ++a) out.header.add_origin(lo[a]);
  out.header.set_step(step);
  out.header.set_extent(extent);
  out.header.set_refinement_planes(static_cast<uint32_t>(planes));

  // The chain in the remesh's units: mean squared error x its vertices.
  const double vertices = static_cast<double>(std::max<uint64_t>(remesh_vertices, 1));
  // Never below the coarse positions' own error: a chain only falls.
  out.chain_start = std::max(remesh_error, std::pow(std::ldexp(step, planes), 2) / 4) * vertices;
  out.reduction.push_back(0);  // the connectivity alone changes no position
  double before = out.chain_start;
  for (int s = planes; s >= 0; --s) {
    const double after = std::pow(std::ldexp(step, s), 2) / 4 * vertices;
    out.reduction.push_back(std::max(before - after, 0.0));
    before = std::min(before, after);
  }
  return out;
}

}  // namespace meshwave::original
