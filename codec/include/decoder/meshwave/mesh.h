// TriMesh: an indexed triangle mesh, and its bytes in PLY and OBJ (what a
// decoder hands out). Reading files, cleaning and statistics:
// meshwave/mesh_io.h, mesh_clean.h, mesh_stats.h (meshwave_codec).
#ifndef MESHWAVE_MESH_H_
#define MESHWAVE_MESH_H_

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3
#include <array>
#include <span>
#include <cstdint>
#include <string>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

using Vec3 = Eigen::Vector3d;
using Face = std::array<uint32_t, 3>;

struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<Face> faces;  // counter-clockwise seen from outside
};

// Binary PLY (float32) and OBJ (shortest exact decimals: lossless) bytes
// of a mesh (WriteMesh, meshwave/mesh_io.h, writes them to files;
// SerializeGltf: meshwave/gltf.h). With `colors` (linear RGB in [0, 1],
// one per vertex; clamped) the PLY's vertices also have uchar red, green
// and blue, sRGB-encoded as PLY colours are by convention.
std::string SerializePly(const TriMesh& mesh, std::span<const Vec3> colors = {});
std::string SerializeObj(const TriMesh& mesh);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_H_
