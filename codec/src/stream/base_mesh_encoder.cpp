#include "stream/base_mesh_encoder.h"

#include <cmath>
#include <string>

#include "entropy/adaptive_golomb_encoder.h"
#include "stream/base_positions.h"
#include "stream/stream_format.h"

namespace meshwave {

Result<BaseMeshOrder> ChooseTransmissionOrder(uint32_t vertex_count,
                                              const std::vector<Face>& faces) {
  return TraverseBaseMesh(vertex_count, faces, nullptr);
}

Result<EncodedBaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces, double step,
                                       uint32_t refinement_planes) {
  if (positions.empty() || faces.empty()) return InvalidArgument("empty base mesh");
  if (!(step > 0) || !std::isfinite(step)) {
    return InvalidArgument("base quantisation step must be positive");
  }
  if (refinement_planes > kMaxBaseRefinementPlanes) {
    return InvalidArgument("at most " + std::to_string(kMaxBaseRefinementPlanes) +
                           " base refinement planes");
  }
  Vec3 origin = positions[0];
  for (const Vec3& p : positions) origin = origin.cwiseMin(p);
  const int64_t low = (int64_t{1} << refinement_planes) - 1;
  std::vector<IntVec3> grid(positions.size());
  EncodedBaseMesh out;
  out.residual.assign(positions.size(), IntVec3{0, 0, 0});
  for (size_t v = 0; v < positions.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const double x = std::round((positions[v][a] - origin[a]) / step);
      if (!(x >= 0) || x >= 2147483647.0) {
        return InvalidArgument("base mesh does not fit a 31-bit grid at this precision");
      }
      const auto fine = static_cast<int64_t>(x);
      grid[v][a] = fine >> refinement_planes;
      out.residual[v][a] = fine & low;
    }
  }
  ArithmeticEncoder enc;
  MW_ASSIGN_OR_RETURN(const BaseMeshOrder order,
                      TraverseBaseMesh(static_cast<uint32_t>(positions.size()), faces, &enc));
  if (order.faces != faces) {
    return Status(StatusCode::kInternal, "base faces are not in transmission order");
  }
  if (order.used_vertices != positions.size()) {
    return Status(StatusCode::kInternal, "base faces do not use every vertex");
  }
  const uint32_t next_new = order.used_vertices;
  const PositionPredictor predictor(faces, next_new);
  PositionContexts pc;
  for (uint32_t v = 0; v < next_new; ++v) {
    const IntVec3 p = predictor.Predict(v, grid);
    for (int a = 0; a < 3; ++a) EncodeSignedGolomb(enc, pc.residual[a], grid[v][a] - p[a]);
  }
  StreamHeader::BaseMesh& base = out.header;
  base.vertex_count = static_cast<uint32_t>(positions.size());
  base.face_count = static_cast<uint32_t>(faces.size());
  for (int a = 0; a < 3; ++a) base.origin.push_back(origin[a]);
  base.step = step;
  base.coded = enc.Finish();
  base.refinement_planes = refinement_planes;
  return out;
}

}  // namespace meshwave
