// The base mesh M^0 on an integer grid, coded with fixed-width bits.
#ifndef MESHWAVE_STREAM_BASE_MESH_CODEC_H_
#define MESHWAVE_STREAM_BASE_MESH_CODEC_H_

#include <vector>

#include "bitplane/coefficient_octree.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "stream.pb.h"

namespace meshwave {

struct DecodedBase {
  std::vector<Vec3> positions;  // origin + step * grid
  std::vector<IntVec3> grid;
  std::vector<Face> faces;
};

// Quantises `positions` with `step` and codes them and the faces.
Result<proto::BaseMesh> EncodeBaseMesh(const std::vector<Vec3>& positions,
                                       const std::vector<Face>& faces,
                                       double step);

// Safe on untrusted input: counts are checked against the coded bytes and
// `max_vertices` before anything is allocated.
Result<DecodedBase> DecodeBaseMesh(const proto::BaseMesh& base,
                                   uint32_t max_vertices);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_MESH_CODEC_H_
