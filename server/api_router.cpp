#include "api_router.h"

#include <spdlog/spdlog.h>

#include "mesh_handlers.h"
#include "meshwave/mesh_id.h"
#include "meshwave/request_target.h"
#include "original_handlers.h"
#include "response.h"
#include "upload_handler.h"
#include "viewer_files.h"

namespace meshwave::server {
namespace {

Response MethodNotAllowed(std::string_view allow) {
  Response r = JsonError(http::status::method_not_allowed, "method not allowed here");
  r.set(http::field::allow, allow);
  return r;
}

bool IsWebSocketEndpoint(const RequestTarget& t) {
  return t.segments.size() == 2 && t.segments[0] == "v1" && t.segments[1] == "ws";
}

bool IsMeshesRoot(const RequestTarget& t) {
  return t.segments.size() == 2 && t.segments[0] == "v1" && t.segments[1] == "meshes";
}

Response Route(ServerContext& ctx, const Request& req, const RequestTarget& t) {
  const auto& seg = t.segments;
  const auto method = req.method();
  const bool get = method == http::verb::get || method == http::verb::head;
  if (seg.size() == 1 && seg[0] == "healthz") {
    if (!get) return MethodNotAllowed("GET, HEAD");
    Response r = Text(http::status::ok, "{\"status\": \"ok\"}\n", "application/json");
    r.set(http::field::cache_control, "no-store");
    return r;
  }
  if (seg.size() == 1 && seg[0] == "metrics") {
    if (!get) return MethodNotAllowed("GET, HEAD");
    const uint64_t meshes = ctx.catalog().Count().ok() ? *ctx.catalog().Count() : 0;
    Response r = Text(http::status::ok, ctx.metrics().Render(meshes, ctx.cache().size()),
                      "text/plain; version=0.0.4");
    r.set(http::field::cache_control, "no-store");
    return r;
  }
  if (IsWebSocketEndpoint(t)) {
    return JsonError(http::status::upgrade_required, "GET /v1/ws needs a WebSocket upgrade");
  }
  if (seg.size() < 2 || seg[0] != "v1" || seg[1] != "meshes") {
    return JsonError(http::status::not_found, "no such endpoint");
  }
  if (seg.size() == 2) {
    if (!get) return MethodNotAllowed("GET, HEAD, POST");
    return ListMeshes(ctx, req, t.query);
  }
  const std::string& id = seg[2];
  if (!IsValidMeshId(id)) {
    return JsonError(http::status::bad_request, "invalid mesh id (12 lowercase hex digits)");
  }
  if (seg.size() == 3) {
    if (method == http::verb::delete_) {
      if (!t.query.empty()) return JsonError(http::status::bad_request, "DELETE takes no query");
      return DeleteMesh(ctx, id);
    }
    if (!get) return MethodNotAllowed("GET, HEAD, DELETE");
    if (!t.query.empty()) return JsonError(http::status::bad_request, "unexpected query");
    return DescribeMesh(ctx, req, id);
  }
  const std::string& what = seg[3];
  if (what == "original") {
    if (!get) return MethodNotAllowed("GET, HEAD");
    if (!t.query.empty()) return JsonError(http::status::bad_request, "unexpected query");
    std::string file;
    for (size_t i = 4; i < seg.size(); ++i) file += (i > 4 ? "/" : "") + seg[i];
    return GetOriginal(ctx, req, id, file);
  }
  const bool known = (seg.size() == 4 && (what == "header" || what == "stream" || what == "container")) ||
                     (seg.size() == 5 && what == "packets");
  if (!known) return JsonError(http::status::not_found, "no such endpoint");
  if (!get) return MethodNotAllowed("GET, HEAD");
  if (what == "stream") return GetStream(ctx, req, id, t.query);
  if (!t.query.empty()) return JsonError(http::status::bad_request, "unexpected query");
  if (what == "header") return GetHeader(ctx, req, id);
  if (what == "container") return GetContainer(ctx, req, id);
  return GetPacket(ctx, req, id, seg[4]);
}

}  // namespace

std::optional<std::string> ResponseCacheKey(const http::request_header<>& req) {
  if (req.method() != http::verb::get && req.method() != http::verb::head) return std::nullopt;
  const std::string_view target = req.target();
  // The mesh endpoints: /v1/meshes/{id}[/...] (Route's seg.size() >= 3).
  if (!target.starts_with("/v1/meshes/") || !req[http::field::if_none_match].empty()) {
    return std::nullopt;
  }
  // The target, plus Range and If-Range when there are any: the only other
  // request fields the mesh endpoints read.
  std::string key(target);
  const std::string_view range = req[http::field::range];
  const std::string_view if_range = req[http::field::if_range];
  if (!range.empty() || !if_range.empty()) {
    key += '\n';
    key.append(range.data(), range.size());
    key += '\n';
    key.append(if_range.data(), if_range.size());
  }
  return key;
}

HeaderDecision InspectHeader(const ServerContext& ctx, const http::request_header<>& header) {
  HeaderDecision d;
  const auto method = header.method();
  if (method != http::verb::post && method != http::verb::delete_) return d;
  auto target = ParseRequestTarget(header.target());
  if (!target.ok()) {
    // The 400 HandleRequest would give, before reading a body that no
    // route can take (the fuzzer sent a POST with a malformed query).
    d.reject = StatusError(target.status());
    return d;
  }
  const bool meshes = target->segments.size() >= 2 && target->segments[0] == "v1" &&
                      target->segments[1] == "meshes";
  if (!meshes) return d;
  // Only routes that exist need a token; the rest get 404/405 later.
  const bool upload = method == http::verb::post && IsMeshesRoot(*target);
  const bool del = method == http::verb::delete_ && target->segments.size() == 3;
  if (!upload && !del) return d;
  d.reject = CheckAuthorization(ctx, header);
  d.upload = upload && !d.reject;
  return d;
}

void HandleRequest(ServerContext& ctx, Request req, std::function<void(Response)> done) {
  try {
    if (IsViewerTarget(req.target())) return done(ServeViewerFile(ctx, req));
    auto target = ParseRequestTarget(req.target());
    if (!target.ok()) return done(StatusError(target.status()));
    // Checked again here so that no caller can skip InspectHeader's check.
    const bool del = req.method() == http::verb::delete_ && target->segments.size() == 3 &&
                     target->segments[0] == "v1" && target->segments[1] == "meshes";
    const bool upload = req.method() == http::verb::post && IsMeshesRoot(*target);
    if (upload || del) {
      if (auto refusal = CheckAuthorization(ctx, req)) return done(std::move(*refusal));
    }
    if (upload) {
      const QueryParams query = target->query;
      return UploadMesh(ctx, std::move(req), query, std::move(done));
    }
    return done(Route(ctx, req, *target));
  } catch (const std::exception& e) {
    // Library exceptions stop here: a 500, never a dead server.
    spdlog::error("{} {}: {}", std::string(req.method_string()), std::string(req.target()), e.what());
    return done(JsonError(http::status::internal_server_error, "internal error"));
  }
}

std::optional<Response> CheckWebSocketUpgrade(ServerContext& ctx,
                                              const http::request_header<>& header) {
  // The path alone decides 404 (anything but /v1/ws, malformed paths and a
  // trailing '/' included); then any query at all, even a malformed one, 400.
  const std::string_view raw = header.target();
  const size_t q = raw.find('?');
  auto path = ParseRequestTarget(raw.substr(0, q));
  if (!path.ok() || !IsWebSocketEndpoint(*path)) {
    return JsonError(http::status::not_found, "WebSocket upgrades go to /v1/ws only");
  }
  if (q != std::string_view::npos) return JsonError(http::status::bad_request, "/v1/ws takes no query");
  const bool full = ctx.metrics().websocket_connections() >=
                    static_cast<int64_t>(ctx.config().max_websocket_sessions());
  if (ctx.stopping() || full) {
    Response r = JsonError(http::status::service_unavailable,
                           full ? "too many WebSocket sessions" : "the server is stopping");
    r.set(http::field::retry_after, "1");
    return r;
  }
  return std::nullopt;
}

}  // namespace meshwave::server
