#include "upload_files.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "meshwave/file_set.h"
#include "multipart_form.h"

namespace meshwave::server {

bool IsMeshFileName(std::string_view name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string_view::npos || name.find('/', dot) != std::string_view::npos) return false;
  std::string ext(name.substr(dot + 1));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == "glb" || ext == "gltf" || ext == "obj" || ext == "ply" || ext == "off";
}

Result<UploadFiles> FilesOfMultipart(std::string_view body, std::string_view boundary,
                                     const std::optional<std::string>& main) {
  MW_ASSIGN_OR_RETURN(std::vector<FormPart> form, ParseMultipartForm(body, boundary));
  UploadFiles files;
  std::set<std::string, std::less<>> names;
  std::vector<std::string> meshes;
  for (const FormPart& part : form) {
    if (part.filename.empty()) {
      return InvalidArgument("multipart part '" + part.name.substr(0, 80) +
                             "' has no filename: each part is a file, named by its filename");
    }
    MW_RETURN_IF_ERROR(CheckFileSetName(part.filename));
    MW_RETURN_IF_ERROR(CheckOriginalFileName(part.filename));
    if (!names.insert(part.filename).second) {
      return InvalidArgument("two parts are named '" + part.filename + "'");
    }
    if (IsMeshFileName(part.filename)) meshes.push_back(part.filename);
    files.parts.push_back({part.filename, part.bytes});
  }
  if (main) {
    if (!names.count(*main)) {
      return InvalidArgument("main='" + main->substr(0, 80) + "' names none of the parts");
    }
    if (!IsMeshFileName(*main)) {
      return InvalidArgument("main='" + *main + "' is not a mesh file (.glb, .gltf, .obj, .ply, .off)");
    }
    files.main = *main;
    return files;
  }
  if (meshes.empty()) {
    return Status(StatusCode::kNotFound,
                  "no part is a mesh file (.glb, .gltf, .obj, .ply or .off, by its filename)");
  }
  if (meshes.size() > 1) {
    return InvalidArgument("parts '" + meshes[0] + "' and '" + meshes[1] +
                           "' are both mesh files: say which one to read with main=");
  }
  files.main = meshes[0];
  return files;
}

AssetLimits UploadAssetLimits(const proto::ServerConfig& config) {
  AssetLimits limits;
  if (config.upload_limit_bytes() > 0) {
    limits.max_file_bytes = std::min(limits.max_file_bytes, config.upload_limit_bytes());
  }
  if (config.ingest_memory_limit_bytes() > 0) {
    limits.max_image_bytes =
        std::min(limits.max_image_bytes, config.ingest_memory_limit_bytes() / 4);
    limits.max_image_pixels = std::min(limits.max_image_pixels, limits.max_image_bytes / 4);
  }
  return limits;
}

}  // namespace meshwave::server
