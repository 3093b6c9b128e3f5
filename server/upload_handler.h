// The authenticated endpoints: POST /v1/meshes (upload and ingest a mesh
// file or a mesh with its files) and DELETE /v1/meshes/{id}. A bearer token from the configuration
// guards both; without a configured token they are refused (403).
#ifndef MESHWAVE_SERVER_UPLOAD_HANDLER_H_
#define MESHWAVE_SERVER_UPLOAD_HANDLER_H_

#include <functional>
#include <optional>
#include <string>

#include "meshwave/request_target.h"
#include "server_context.h"
#include "slices_body.h"

namespace meshwave::server {

// Null when the request carries the configured token; else 401 (no or
// malformed Authorization) or 403 (wrong token, or uploads disabled).
// Called on the header alone, before an upload body is read.
std::optional<Response> CheckAuthorization(const ServerContext& ctx,
                                           const http::request_header<>& header);

// Parses, remeshes when needed, encodes and stores the upload (one mesh
// file, or a multipart/form-data body of a mesh and its files: checked
// here, 400/422 before any work is queued) on the ingest worker, then
// calls `done` there with 201 (new), 200 (already present) or a 4xx/5xx
// error.
void UploadMesh(ServerContext& ctx, Request req, const QueryParams& query,
                std::function<void(Response)> done);

Response DeleteMesh(ServerContext& ctx, const std::string& id);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_UPLOAD_HANDLER_H_
