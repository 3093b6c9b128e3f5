#include "server_config.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "ingest.h"
#include "meshwave/request_target.h"
#include "viewer_files.h"

namespace meshwave::server {
namespace {

class CollectErrors : public google::protobuf::io::ErrorCollector {
 public:
  void AddError(int line, int column, const std::string& message) override {
    if (first.empty()) {
      first = "line " + std::to_string(line + 1) + ", column " +
              std::to_string(column + 1) + ": " + message;
    }
  }
  std::string first;
};

}  // namespace

Result<proto::ServerConfig> LoadServerConfig(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return IoError("cannot read config " + path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  proto::ServerConfig config;
  google::protobuf::TextFormat::Parser parser;
  CollectErrors errors;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(ss.str(), &config)) {
    return ParseError(path.string() + ": " + errors.first);
  }
  return config;
}

Status FinishServerConfig(proto::ServerConfig& c) {
  if (c.listen().empty()) c.set_listen("127.0.0.1:8080");
  if (c.threads() == 0) c.set_threads(2);
  if (c.max_connections() == 0) c.set_max_connections(1024);
  if (c.header_limit_bytes() == 0) c.set_header_limit_bytes(16 * 1024);
  if (c.body_limit_bytes() == 0) c.set_body_limit_bytes(64 * 1024);
  if (c.upload_limit_bytes() == 0) c.set_upload_limit_bytes(64ull << 20);
  if (c.idle_timeout_seconds() == 0) c.set_idle_timeout_seconds(30);
  if (c.write_timeout_seconds() == 0) c.set_write_timeout_seconds(120);
  if (c.open_containers() == 0) c.set_open_containers(64);
  if (c.shutdown_grace_seconds() == 0) c.set_shutdown_grace_seconds(10);
  if (c.header_timeout_seconds() == 0) c.set_header_timeout_seconds(10);
  if (c.rate_limit_burst() == 0) c.set_rate_limit_burst(2 * c.rate_limit_requests_per_second());
  if (c.max_websocket_sessions() == 0) c.set_max_websocket_sessions(10000);
  if (c.websocket_message_limit_bytes() == 0) c.set_websocket_message_limit_bytes(64 * 1024);
  if (c.websocket_ping_seconds() == 0) c.set_websocket_ping_seconds(15);
  if (!c.has_response_cache_bytes()) c.set_response_cache_bytes(uint64_t{32} << 20);
  if (c.viewer_dir().empty()) c.set_viewer_dir(DefaultViewerDir().string());
  if (!c.has_ingest_nice()) c.set_ingest_nice(10);
  if (c.ingest_nice() > 19) return InvalidArgument("ingest_nice must be 0 to 19");
  if (c.catalog_poll_milliseconds() == 0) c.set_catalog_poll_milliseconds(1000);
  if (c.retired_container_seconds() == 0) {
    c.set_retired_container_seconds(static_cast<uint32_t>(kDefaultRetiredSeconds));
  }
  if (const char* token = std::getenv("MESHWAVE_UPLOAD_TOKEN"); token && *token) {
    c.set_upload_token(token);
  }
  if (c.threads() > 256) return InvalidArgument("threads must be at most 256");
  if (c.header_limit_bytes() < 1024) return InvalidArgument("header_limit_bytes must be at least 1024");
  MW_RETURN_IF_ERROR(ParseListenAddress(c.listen()).status());
  return Status::Ok();
}

Result<ListenAddress> ParseListenAddress(const std::string& text) {
  const size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    return InvalidArgument("listen address '" + text + "' is not host:port");
  }
  ListenAddress a;
  a.host = text.substr(0, colon);
  if (a.host.size() > 2 && a.host.front() == '[' && a.host.back() == ']') {
    a.host = a.host.substr(1, a.host.size() - 2);
  }
  auto port = ParseUnsigned(text.substr(colon + 1), 65535, "port");
  if (!port.ok()) return InvalidArgument("listen address '" + text + "': " + port.status().message());
  a.port = static_cast<uint16_t>(*port);
  return a;
}

}  // namespace meshwave::server
