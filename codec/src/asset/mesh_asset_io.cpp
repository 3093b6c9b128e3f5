// ParseMeshAsset and ReadMeshAsset: the format by extension, the main file
// read from the file set, then the format's reader. PLY and OFF, whose
// readers live with the geometry readers (mesh/), are read here: this file
// is part of meshwave_codec (codec/asset.cmake), which has both.
#include <cctype>
#include <string>
#include <utility>

#include "asset/asset_readers.h"
#include "asset/srgb.h"
#include "asset/weld.h"
#include "mesh/ply_header.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/mesh_io.h"

namespace meshwave {
namespace {

std::string LowerExtension(std::string_view name) {
  const size_t dot = name.rfind('.');
  const size_t slash = name.rfind('/');
  if (dot == std::string_view::npos ||
      (slash != std::string_view::npos && dot < slash)) {
    return "";
  }
  std::string ext(name.substr(dot));
  for (char& c : ext) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext;
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

Result<MeshAsset> ParsePlyAsset(std::string_view bytes, std::string_view name) {
  MW_ASSIGN_OR_RETURN(PlyColoredMesh ply, ParsePlyWithColors(bytes, name));
  if (ply.mesh.faces.empty()) {
    return ParseError(std::string(name) + ": no faces (" +
                      std::to_string(ply.mesh.positions.size()) + " vertices)");
  }
  MeshAsset asset;
  asset.mesh = std::move(ply.mesh);
  const PlyMeshLayout& layout = ply.header.layout;
  if (!ply.colors.empty()) {
    asset.color.values.reserve(ply.colors.size());
    for (const Eigen::Vector4f& c : ply.colors) {
      asset.color.values.emplace_back(SrgbToLinear(c[0]), SrgbToLinear(c[1]),
                                      SrgbToLinear(c[2]), c[3]);
    }
    asset.color.faces = asset.mesh.faces;
  }
  // What else the file holds.
  const std::string prefix = std::string(name) + ": ";
  std::vector<std::string> normals;
  std::vector<std::string> vertex_other;
  std::vector<std::string> face_other;
  std::vector<std::string> elements;
  for (size_t i = 0; i < ply.header.elements.size(); ++i) {
    const PlyElement& e = ply.header.elements[i];
    if (i == layout.vertex_element) {
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const std::string& n = e.properties[p].name;
        const bool position =
            p == layout.xyz[0] || p == layout.xyz[1] || p == layout.xyz[2];
        const bool color =
            layout.HasColors() && (p == layout.rgba[0] || p == layout.rgba[1] ||
                                   p == layout.rgba[2] || p == layout.rgba[3]);
        if (position || color) continue;
        (n == "nx" || n == "ny" || n == "nz" ? normals : vertex_other)
            .push_back(n.substr(0, 40));
      }
    } else if (i == layout.face_element) {
      for (size_t p = 0; p < e.properties.size(); ++p) {
        if (p != layout.indices)
          face_other.push_back(e.properties[p].name.substr(0, 40));
      }
    } else if (e.count > 0) {
      elements.push_back(e.name.substr(0, 40));
    }
  }
  if (!normals.empty()) {
    asset.notes.push_back(prefix + "vertex normals (" + JoinNames(normals) +
                          ") not carried (recomputed from the surface)");
  }
  if (!vertex_other.empty()) {
    asset.notes.push_back(
        prefix + "vertex properties " + JoinNames(vertex_other) +
        " not carried" +
        (layout.HasColors() ? "" : " (colours need red, green and blue)"));
  }
  if (!face_other.empty()) {
    asset.notes.push_back(prefix + "face properties " + JoinNames(face_other) +
                          " not carried");
  }
  if (!elements.empty()) {
    asset.notes.push_back(prefix + "elements " + JoinNames(elements) +
                          " not carried");
  }
  WeldPositions(asset.mesh);
  return asset;
}

Result<MeshAsset> ParseOffAsset(std::string_view bytes, std::string_view name) {
  MeshAsset asset;
  MW_ASSIGN_OR_RETURN(asset.mesh, ParseMesh(bytes, MeshFormat::kOff, name));
  // The header keyword says whether colours (C) or normals (N) follow.
  size_t start = 0;
  while (start < bytes.size() &&
         std::isspace(static_cast<unsigned char>(bytes[start]))) {
    ++start;
  }
  const std::string_view head = bytes.substr(start, 8);
  const size_t length = head.find_first_of(" \t\r\n");
  const std::string_view keyword = head.substr(0, length);
  if (keyword.find('C') != std::string_view::npos && keyword.ends_with("OFF")) {
    asset.notes.push_back(std::string(name) +
                          ": OFF vertex colours not carried (use PLY for "
                          "coloured meshes)");
  }
  if (keyword.find('N') != std::string_view::npos && keyword.ends_with("OFF")) {
    asset.notes.push_back(std::string(name) +
                          ": OFF vertex normals not carried (recomputed from "
                          "the surface)");
  }
  WeldPositions(asset.mesh);
  return asset;
}

}  // namespace

Result<MeshAsset> ParseMeshAsset(FileSet& files, std::string_view main_file,
                                 const AssetLimits& limits) {
  const std::string ext = LowerExtension(main_file);
  if (ext != ".glb" && ext != ".gltf" && ext != ".obj" && ext != ".ply" &&
      ext != ".off") {
    return InvalidArgument(std::string(main_file) + ": unknown mesh format \"" +
                           ext +
                           "\" (expected .glb, .gltf, .obj, .ply or .off)");
  }
  MW_ASSIGN_OR_RETURN(const std::string_view bytes, files.Read(main_file));
  if (bytes.size() > limits.max_file_bytes) {
    return Status(StatusCode::kUnsupported,
                  std::string(main_file) + ": " + std::to_string(bytes.size()) +
                      " bytes, more than the " +
                      std::to_string(limits.max_file_bytes) + "-byte limit");
  }
  if (ext == ".glb" || ext == ".gltf") {
    return ParseGltfAsset(bytes, files, main_file, limits);
  }
  if (ext == ".obj") return ParseObjAsset(bytes, files, main_file, limits);
  if (ext == ".ply") return ParsePlyAsset(bytes, main_file);
  return ParseOffAsset(bytes, main_file);
}

Result<MeshAsset> ReadMeshAsset(const std::filesystem::path& path,
                                const AssetLimits& limits) {
  const std::filesystem::path folder =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  DirectoryFileSet files(folder, limits.max_file_bytes);
  Result<MeshAsset> asset =
      ParseMeshAsset(files, path.filename().string(), limits);
  return asset;
}

}  // namespace meshwave
