// The browser viewer's static files (web/viewer), served under /viewer/
// from the directory ServerConfig.viewer_dir names: GET and HEAD only,
// Content-Type by extension, a strong ETag (the content's SHA-256) with
// Cache-Control "no-cache" (kept by the browser, revalidated with a cheap
// 304, so an upgraded server never runs a stale page), 404 for a missing
// file, and no way out of the directory (".." and encoded slashes are
// refused by ParseRequestTarget, symlinks leading out by a canonical-path
// check).
#ifndef MESHWAVE_SERVER_VIEWER_FILES_H_
#define MESHWAVE_SERVER_VIEWER_FILES_H_

#include <filesystem>
#include <string_view>

#include "server_context.h"
#include "slices_body.h"

namespace meshwave::server {

// True for "/viewer" and "/viewer/..." (query included or not).
bool IsViewerTarget(std::string_view target);

// The response to a request whose target IsViewerTarget.
Response ServeViewerFile(const ServerContext& ctx, const Request& req);

// "text/html; charset=utf-8" for .html and so on; application/octet-stream
// for an extension not listed.
std::string_view ViewerContentType(const std::filesystem::path& file);

// Where the viewer is when the configuration names no directory: the
// installed copy (<prefix>/share/meshwave/viewer beside <prefix>/bin of the
// running executable) when it exists, else the build tree's copy.
std::filesystem::path DefaultViewerDir();

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_VIEWER_FILES_H_
