// The files of an upload to POST /v1/meshes: one mesh file as the whole
// body, or several (a mesh and its sidecar files) as the parts of a
// multipart/form-data body, each named by its filename. Shared by the
// handler, which checks them before any work is queued, and the upload
// worker, which reads them again from the same body.
#ifndef MESHWAVE_SERVER_UPLOAD_FILES_H_
#define MESHWAVE_SERVER_UPLOAD_FILES_H_

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"
#include "original_store.h"
#include "server_config.pb.h"

namespace meshwave::server {

struct UploadFiles {
  std::vector<OriginalPart> parts;  // views into the body
  std::string main;                 // the mesh file a reader opens
};

// Whether a file name's extension (any case) is a mesh format the ingest
// reads: .glb, .gltf, .obj, .ply, .off.
bool IsMeshFileName(std::string_view name);

// The files of a multipart/form-data body framed by `boundary`: each part a
// file named by its filename (CheckFileSetName and CheckOriginalFileName
// hold; the form field names do not matter). The main file is `main` when
// given (it must be one of them, with a mesh extension), else the one part
// whose name has a mesh extension. kParseError for a malformed or truncated
// body (ParseMultipartForm); kInvalidArgument for a part without a
// filename, a bad or repeated name, `main` naming no part or no mesh, or
// two mesh files and no `main`; kNotFound when no part is a mesh file.
Result<UploadFiles> FilesOfMultipart(std::string_view body, std::string_view boundary,
                                     const std::optional<std::string>& main);

// What reading an upload may take: AssetLimits' defaults lowered to the
// server's configuration. Its files together are at most the upload limit;
// with an ingest memory limit, decoded images take at most a quarter of it.
AssetLimits UploadAssetLimits(const proto::ServerConfig& config);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_UPLOAD_FILES_H_
