#include "stream/base_mesh_decoder.h"

#include <cmath>
#include <string>

#include "entropy/adaptive_golomb_decoder.h"
#include "stream/base_connectivity_decoder.h"
#include "stream/base_positions.h"
#include "stream/base_refinement.h"
#include "stream/base_refinement_decoder.h"
#include "stream/stream_format.h"

namespace meshwave {

Result<DecodedBase> DecodeBaseMesh(const StreamHeader::BaseMesh& base, uint32_t max_vertices) {
  const uint64_t v = base.vertex_count, f = base.face_count;
  if (v < 3 || f == 0) return ParseError("base mesh: too few vertices or no faces");
  if (v > max_vertices) {
    return ParseError("base mesh: " + std::to_string(v) + " vertices exceed the limit of " +
                      std::to_string(max_vertices));
  }
  // A manifold mesh has F = 2V - 4 + 4g - (boundary terms) faces: this bound
  // leaves room for genus up to V/2 and stops absurd counts.
  if (f > 4 * v + 64) {
    return ParseError("base mesh: " + std::to_string(f) + " faces for " +
                      std::to_string(v) + " vertices");
  }
  if (base.origin.size() != 3 || !(base.step > 0) || !std::isfinite(base.step)) {
    return ParseError("base mesh: bad origin or step");
  }
  for (double o : base.origin) {
    if (!std::isfinite(o)) return ParseError("base mesh: origin is not finite");
  }
  if (base.refinement_planes > kMaxBaseRefinementPlanes) {
    return ParseError("base mesh: " + std::to_string(base.refinement_planes) +
                      " refinement planes (at most " +
                      std::to_string(kMaxBaseRefinementPlanes) + ")");
  }
  // Finest-grid coordinates, 2^R times the coarse ones, stay below 2^31.
  const int64_t grid_limit = int64_t{0x7fffffff} >> base.refinement_planes;
  ArithmeticDecoder dec(base.coded);
  DecodedBase out;
  MW_ASSIGN_OR_RETURN(out.faces,
                      DecodeBaseConnectivity(dec, static_cast<uint32_t>(v), f));
  const uint32_t next_new = static_cast<uint32_t>(v);
  const PositionPredictor predictor(out.faces, next_new);
  PositionContexts pc;
  out.grid.resize(v);
  out.positions.resize(v);
  for (uint32_t i = 0; i < v; ++i) {
    const IntVec3 p = predictor.Predict(i, out.grid);
    for (int a = 0; a < 3; ++a) {
      const int64_t q = p[a] + DecodeSignedGolomb(dec, pc.residual[a]);
      if (q < 0 || q > grid_limit) {
        return ParseError("base mesh: vertex " + std::to_string(i) + " leaves the grid");
      }
      out.grid[i][a] = q;
    }
  }
  if (dec.overrun()) return ParseError("base mesh: coded bytes truncated");
  ForgetBaseRefinement(base, out);
  return out;
}

Status RefineBase(const StreamHeader::BaseMesh& header, int plane, std::string_view payload,
                  DecodedBase& base) {
  if (plane != base.missing_planes - 1) {
    return InvalidArgument("base refinement plane " + std::to_string(plane) +
                           " out of turn (next: " + std::to_string(base.missing_planes - 1) +
                           ")");
  }
  MW_RETURN_IF_ERROR(DecodeBaseRefinementPlane(payload, plane, base.refinement));
  base.missing_planes = plane;
  for (size_t v = 0; v < base.grid.size(); ++v) {
    base.positions[v] = RefinedBasePosition(header, base.grid[v], base.refinement[v], plane);
  }
  return Status::Ok();
}

void ForgetBaseRefinement(const StreamHeader::BaseMesh& header, DecodedBase& base) {
  base.missing_planes = static_cast<int>(header.refinement_planes);
  base.refinement.assign(base.grid.size(), IntVec3{0, 0, 0});
  base.positions.resize(base.grid.size());
  for (size_t v = 0; v < base.grid.size(); ++v) {
    base.positions[v] =
        RefinedBasePosition(header, base.grid[v], base.refinement[v], base.missing_planes);
  }
}

}  // namespace meshwave
