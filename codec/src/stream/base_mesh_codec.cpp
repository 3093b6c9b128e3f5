#include "stream/base_mesh_codec.h"

#include <cmath>
#include <string>
#include <unordered_map>

#include "core/edge_key.h"
#include "entropy/adaptive_golomb.h"
#include "stream/stream_format.h"

namespace meshwave {
namespace {

// Contexts of the position code.
struct PositionContexts {
  SignedGolombContexts residual[3];
};

// The prediction of vertex v's grid position from vertices < v: across an
// edge of the face where v first appears (parallelogram), else the mean of
// that face's known corners, else the previous vertex.
class PositionPredictor {
 public:
  PositionPredictor(const std::vector<Face>& faces, uint32_t vertex_count)
      : faces_(faces), first_face_(vertex_count, kNoFace) {
    for (uint32_t f = 0; f < faces.size(); ++f) {
      for (int c = 0; c < 3; ++c) {
        const uint32_t v = faces[f][c];
        if (first_face_[v] == kNoFace) first_face_[v] = f;
        auto [it, fresh] = edge_faces_.try_emplace(
            EdgeKey(v, faces[f][(c + 1) % 3]), std::array<uint32_t, 2>{kNoFace, kNoFace});
        (it->second[0] == kNoFace ? it->second[0] : it->second[1]) = f;
      }
    }
  }

  IntVec3 Predict(uint32_t v, const std::vector<IntVec3>& grid) const {
    const uint32_t f = first_face_[v];
    uint32_t known[2];
    int n = 0;
    if (f != kNoFace) {
      for (uint32_t u : faces_[f]) {
        if (u < v && n < 2) known[n++] = u;
      }
    }
    if (n == 2) {
      auto it = edge_faces_.find(EdgeKey(known[0], known[1]));
      if (it != edge_faces_.end()) {
        for (uint32_t g : it->second) {
          if (g == kNoFace || g == f) continue;
          for (uint32_t c : faces_[g]) {
            if (c != known[0] && c != known[1] && c < v) {
              IntVec3 p;
              for (int a = 0; a < 3; ++a) {
                p[a] = grid[known[0]][a] + grid[known[1]][a] - grid[c][a];
              }
              return p;
            }
          }
        }
      }
      IntVec3 p;
      for (int a = 0; a < 3; ++a) p[a] = (grid[known[0]][a] + grid[known[1]][a]) >> 1;
      return p;
    }
    if (n == 1) return grid[known[0]];
    if (v > 0) return grid[v - 1];
    return {0, 0, 0};
  }

 private:
  static constexpr uint32_t kNoFace = 0xffffffffu;
  const std::vector<Face>& faces_;
  std::vector<uint32_t> first_face_;
  std::unordered_map<uint64_t, std::array<uint32_t, 2>> edge_faces_;
};

}  // namespace

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
