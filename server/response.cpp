#include "response.h"

#include <google/protobuf/util/json_util.h>

#include <cstdio>

namespace meshwave::server {

std::string JsonQuote(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

Response Text(http::status status, std::string body, std::string_view content_type) {
  Response r{status, 11};
  r.set(http::field::content_type, content_type);
  r.body().owned = std::move(body);
  return r;
}

std::string JsonErrorBody(std::string_view message) {
  return "{\"error\": " + JsonQuote(message) + "}\n";
}

Response JsonError(http::status status, std::string_view message) {
  Response r = Text(status, JsonErrorBody(message), "application/json");
  SetJsonErrorHeaders(r);
  return r;
}

Response StatusError(const Status& status) {
  switch (status.code()) {
    case StatusCode::kInvalidArgument:
    case StatusCode::kParseError:
    case StatusCode::kNeedMoreInput:
    case StatusCode::kNotSemiRegular:
    case StatusCode::kNotManifold:
    case StatusCode::kUnsupported:
      return JsonError(http::status::bad_request, status.message());
    case StatusCode::kNotFound:
      return JsonError(http::status::not_found, status.message());
    case StatusCode::kStale:
      return JsonError(http::status::conflict, status.message());
    default:
      return JsonError(http::status::internal_server_error, status.message());
  }
}

Response Message(const Request& request, const google::protobuf::Message& message,
                 http::status status) {
  const auto accept = request[http::field::accept];
  if (accept.find(kProtobufType) != std::string_view::npos) {
    return Text(status, message.SerializeAsString(), kProtobufType);
  }
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return Text(status, std::move(json), "application/json");
}

void MarkMeshResource(Response& response, const std::string& etag, const std::string& container,
                      bool pinned) {
  response.set(http::field::etag, etag);
  response.set(http::field::cache_control, pinned ? kImmutable : kUnpinned);
  response.set("X-Meshwave-Container", container);
}

}  // namespace meshwave::server
