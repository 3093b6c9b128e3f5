// GET /v1/meshes/{id}/original[/{name}]: a mesh's original, for the holder
// of the upload token only (docs/API.md): it is what a user uploaded, not
// something the catalog publishes.
#ifndef MESHWAVE_SERVER_ORIGINAL_HANDLERS_H_
#define MESHWAVE_SERVER_ORIGINAL_HANDLERS_H_

#include <string>
#include <string_view>

#include "server_context.h"
#include "slices_body.h"

namespace meshwave::server {

// `file` empty: the original's manifest (OriginalInfo, JSON or protobuf);
// else that file's bytes. 401/403 without the token, 404 for a mesh
// without an original or a name it does not list. Never cached.
Response GetOriginal(ServerContext& ctx, const Request& req, const std::string& id,
                     std::string_view file);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_ORIGINAL_HANDLERS_H_
