// Server settings: the ServerConfig message (proto/server_config.proto)
// read from a text-format file, with defaults filled in and the upload
// token taken from MESHWAVE_UPLOAD_TOKEN when that is set.
#ifndef MESHWAVE_SERVER_SERVER_CONFIG_H_
#define MESHWAVE_SERVER_SERVER_CONFIG_H_

#include <filesystem>
#include <string>

#include "meshwave/status.h"
#include "server_config.pb.h"

namespace meshwave::server {

// Parses a text-format ServerConfig; ParseError naming the file and line.
Result<proto::ServerConfig> LoadServerConfig(const std::filesystem::path& path);

// Fills every zero field with its default (documented in docs/API.md) and
// applies MESHWAVE_UPLOAD_TOKEN. kInvalidArgument for values out of range.
Status FinishServerConfig(proto::ServerConfig& config);

struct ListenAddress {
  std::string host;
  uint16_t port = 0;  // 0: any free port
};
// "host:port" or "[v6]:port". kInvalidArgument otherwise.
Result<ListenAddress> ParseListenAddress(const std::string& text);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_SERVER_CONFIG_H_
