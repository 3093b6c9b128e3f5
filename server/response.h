// Building responses: JSON errors, JSON or protobuf messages, immutable
// resources with ETag and Cache-Control.
#ifndef MESHWAVE_SERVER_RESPONSE_H_
#define MESHWAVE_SERVER_RESPONSE_H_

#include <google/protobuf/message.h>

#include <string>
#include <string_view>

#include "meshwave/status.h"
#include "slices_body.h"

namespace meshwave::server {

inline constexpr std::string_view kProtobufType = "application/x-protobuf";
// Mesh responses pinned to their container (docs/API.md, "Re-encoded
// meshes") never change; without the pin the same URL answers from a
// re-encoded container later, so caches keep it a minute, then revalidate
// with the ETag.
inline constexpr std::string_view kImmutable = "public, max-age=31536000, immutable";
inline constexpr std::string_view kUnpinned = "public, max-age=60";

// {"error": "<message>"} with `status`.
Response JsonError(http::status status, std::string_view message);
// The body of JsonError (also of the WebSocket handshake's refusals, which
// Beast writes), and its headers set on any response type.
std::string JsonErrorBody(std::string_view message);
template <typename Fields>
void SetJsonErrorHeaders(Fields& fields) {
  fields.set(http::field::content_type, "application/json");
  fields.set(http::field::cache_control, "no-store");
}
// A Status from the codec or the catalog as a response: client errors
// (invalid argument, parse) as 400, not found as 404, the rest as 500.
Response StatusError(const Status& status);
Response Text(http::status status, std::string body, std::string_view content_type);
// `message` as protobuf when the request's Accept names
// application/x-protobuf, else as JSON (proto3 mapping, .proto field names).
Response Message(const Request& request, const google::protobuf::Message& message,
                 http::status status = http::status::ok);
// Marks a mesh resource: its strong ETag, the container it comes from
// (X-Meshwave-Container) and kImmutable when `pinned`, else kUnpinned.
void MarkMeshResource(Response& response, const std::string& etag, const std::string& container,
                      bool pinned);

// JSON string literal of `s` (quotes included).
std::string JsonQuote(std::string_view s);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_RESPONSE_H_
