// TriMesh: an indexed triangle mesh, and reading, writing, cleaning and
// describing it. Readers are safe on untrusted bytes: every malformed input
// gives a ParseError naming the file and the element or line, never a crash,
// and no allocation is sized by a count before the count is checked against
// the bytes that remain.
#ifndef MESHWAVE_MESH_H_
#define MESHWAVE_MESH_H_

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/status.h"

namespace meshwave {

using Vec3 = Eigen::Vector3d;
using Face = std::array<uint32_t, 3>;

struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<Face> faces;  // counter-clockwise seen from outside
};

enum class MeshFormat { kPly, kObj, kOff, kGltf };

// Guesses the format from the file extension (.ply, .obj, .off; .glb and
// .gltf are kGltf; any case).
Result<MeshFormat> FormatFromPath(const std::filesystem::path& path);

// Parses a whole file held in memory. `name` is used in error messages only.
// PLY: ascii, binary_little_endian, binary_big_endian; vertex x/y/z of any
// scalar type; faces as a list property named vertex_indices or vertex_index;
// other properties and elements are skipped. OBJ: `v` and `f` (polygons
// fan-triangulated, negative indices, v/vt/vn forms); everything else ignored.
// OFF: OFF/COFF/NOFF/CNOFF headers, comments, polygons fan-triangulated.
// glTF: a .glb, or a .gltf whose buffers are data URIs (a file that refers
// to others needs them: ReadMesh, or ParseMeshAsset of meshwave/
// mesh_asset.h); the default scene's triangles with node transforms
// applied, positions welded; images are not read. AssetLimits' defaults
// hold (16.7 M triangles counted per drawing node: instancing is a way to
// make a small file decode to a huge mesh).
// Rejects NaN/Inf coordinates, out-of-range indices, truncated data and empty
// meshes. Polygons with fewer than 3 corners are an error.
Result<TriMesh> ParseMesh(std::string_view bytes, MeshFormat format,
                          std::string_view name);

// Reads and parses a file; the format comes from its extension. Files over
// 4 GiB are refused. IoError (naming the path) when it cannot be read; the
// parse errors name the path as given (glTF's name the file in its folder,
// where its .bin files are read from).
Result<TriMesh> ReadMesh(const std::filesystem::path& path);

// Writes binary PLY (float32), OBJ (shortest exact decimals: lossless) or
// glTF 2.0 (.glb, .gltf: meshwave/gltf.h) by the path's extension. The file
// is written to `<path>.tmp-<pid>`, fsynced and renamed, so a failure never
// leaves half a file behind. IoError names the path; .off gives kUnsupported,
// other extensions kInvalidArgument.
Status WriteMesh(const TriMesh& mesh, const std::filesystem::path& path);
// In-memory forms of the writers (SerializeGltf: meshwave/gltf.h).
std::string SerializePly(const TriMesh& mesh);
std::string SerializeObj(const TriMesh& mesh);

struct CleanOptions {
  bool merge_duplicate_vertices = true;   // bit-identical positions
  bool drop_degenerate_faces = true;      // a repeated corner index
  bool drop_duplicate_faces = true;       // same three vertices, any order
  bool drop_unreferenced_vertices = true;
};

// What cleaning changed, and what it found but left alone.
struct CleanReport {
  size_t merged_vertices = 0;
  size_t degenerate_faces = 0;
  size_t duplicate_faces = 0;
  size_t unreferenced_vertices = 0;
  size_t zero_area_faces = 0;  // distinct corners but no area; kept
};

// Cleans in place. Vertex order is kept (stable compaction); of merged
// vertices and duplicate faces the first one stays. Merged duplicates are
// always removed; `unreferenced_vertices` counts the others whether or not
// they are dropped. Faces must index existing vertices.
CleanReport CleanMesh(TriMesh& mesh, const CleanOptions& options = {});

struct Aabb {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  double Diagonal() const { return (max - min).norm(); }
};
// Bounding box of the positions (of all of them, referenced or not).
Aabb BoundingBox(const std::vector<Vec3>& positions);

// Combinatorial description of a mesh.
struct MeshStats {
  size_t vertices = 0;             // referenced by at least one face
  size_t unreferenced_vertices = 0;
  size_t faces = 0;
  size_t edges = 0;
  size_t boundary_edges = 0;
  size_t boundary_loops = 0;       // counted on manifold boundaries
  size_t components = 0;           // face-connected through shared vertices
  size_t non_manifold_edges = 0;   // more than two faces
  size_t non_manifold_vertices = 0;  // faces around it form several fans
  size_t inconsistently_oriented_edges = 0;  // both faces run it the same way
  bool manifold = false;
  bool closed = false;
  long euler_characteristic = 0;
  // Sum of the genera of the components; only meaningful when manifold.
  long genus = -1;
};
// Faces must index existing vertices. Linear time apart from tiny
// per-vertex sorts. Boundary loops are the connected components of the
// boundary-edge graph, which on a manifold boundary are exactly its cycles.
MeshStats ComputeStats(const TriMesh& mesh);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_H_
