// File-level mesh I/O that needs no asset reader: the format by extension,
// crash-safe writes (core/durable_file.h), and the bounding box. Reading
// (ReadMesh, ParseMesh) is asset/mesh_read.cpp: glTF geometry comes through
// the asset reader, a floor above this one.
#include <cctype>
#include <string>

#include "core/durable_file.h"
#include "meshwave/gltf.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"
#include "meshwave/mesh_stats.h"

namespace meshwave {

Result<MeshFormat> FormatFromPath(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".ply") return MeshFormat::kPly;
  if (ext == ".obj") return MeshFormat::kObj;
  if (ext == ".off") return MeshFormat::kOff;
  if (ext == ".glb" || ext == ".gltf") return MeshFormat::kGltf;
  return InvalidArgument(path.string() + ": unknown mesh format \"" +
                         path.extension().string() +
                         "\" (expected .ply, .obj, .off, .glb or .gltf)");
}

Status WriteMesh(const TriMesh& mesh, const std::filesystem::path& path,
                 std::span<const Vec3> colors) {
  if (const auto gltf = GltfFormFromPath(path)) {
    return WriteFileDurably(path, SerializeGltf(mesh, *gltf, colors));
  }
  const Result<MeshFormat> read_format = FormatFromPath(path);
  if (!read_format.ok()) {
    return InvalidArgument(path.string() + ": unknown mesh format \"" +
                           path.extension().string() +
                           "\" (write .ply, .obj, .glb or .gltf)");
  }
  switch (*read_format) {
    case MeshFormat::kPly:
      return WriteFileDurably(path, SerializePly(mesh, colors));
    case MeshFormat::kObj:
      return WriteFileDurably(path, SerializeObj(mesh));
    case MeshFormat::kOff:
      break;
    case MeshFormat::kGltf:  // handled above (GltfFormFromPath)
      break;
  }
  return Status(
      StatusCode::kUnsupported,
      path.string() +
          ": writing OFF is not supported (use .ply, .obj, .glb or .gltf)");
}

Aabb BoundingBox(const std::vector<Vec3>& positions) {
  Aabb box;
  if (positions.empty()) return box;
  box.min = box.max = positions.front();
  for (const Vec3& p : positions) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

}  // namespace meshwave
