// Routes requests to handlers: the target is parsed and checked first
// (ParseRequestTarget), ids validated (IsValidMeshId), methods matched,
// and anything else answered with a 4xx JSON error.
#ifndef MESHWAVE_SERVER_API_ROUTER_H_
#define MESHWAVE_SERVER_API_ROUTER_H_

#include <functional>
#include <optional>
#include <string>

#include "server_context.h"
#include "slices_body.h"

namespace meshwave::server {

// What a session does once a request's header is read.
struct HeaderDecision {
  std::optional<Response> reject;  // answer this now, without the body
  bool upload = false;             // the body may be as large as an upload
};

// Authentication of POST and DELETE happens here, so that a refused
// upload's body is never read.
HeaderDecision InspectHeader(const ServerContext& ctx, const http::request_header<>& header);

// The key under which the response cache (response_cache.h) keeps the
// answer to `req`, or nothing for a request whose answer must not be kept.
// Declared with the routes: a route whose answer depends on more than the
// target and the Range fields must say so here. Only the mesh endpoints'
// GETs (and HEADs) plan cacheable responses (the others never set
// body().mesh); a conditional GET (If-None-Match) is answered by the
// handlers.
std::optional<std::string> ResponseCacheKey(const http::request_header<>& req);

// Handles a complete request. `done` runs once, on this thread for most
// requests or later on the ingest worker for uploads.
void HandleRequest(ServerContext& ctx, Request req, std::function<void(Response)> done);

// Whether a WebSocket upgrade may go ahead: the refusal to send instead
// (404 for a path other than /v1/ws, 400 for any query, 503 while the server stops or when
// max_websocket_sessions are open), or nothing.
std::optional<Response> CheckWebSocketUpgrade(ServerContext& ctx,
                                              const http::request_header<>& header);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_API_ROUTER_H_
