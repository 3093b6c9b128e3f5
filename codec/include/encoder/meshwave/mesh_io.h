// Reading and writing mesh files. Readers are safe on untrusted bytes:
// every malformed input gives a ParseError naming the file and the element
// or line, never a crash, and no allocation is sized by a count before the
// count is checked against the bytes that remain.
#ifndef MESHWAVE_MESH_IO_H_
#define MESHWAVE_MESH_IO_H_

#include <filesystem>
#include <string_view>

#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

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
// other extensions kInvalidArgument. `colors` (linear RGB, one per vertex)
// go into PLY and glTF files (SerializePly, SerializeGltf); OBJ has no
// standard place for them and leaves them out.
Status WriteMesh(const TriMesh& mesh, const std::filesystem::path& path,
                 std::span<const Vec3> colors = {});
}  // namespace meshwave

#endif  // MESHWAVE_MESH_IO_H_
