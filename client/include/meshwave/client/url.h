// Server and mesh URLs as the client accepts them:
// http(s)://host[:port] and http(s)://host[:port]/v1/meshes/{id}, and the
// same with ws:// and wss://, which choose the WebSocket transport
// (GET /v1/ws on that server).
#ifndef MESHWAVE_CLIENT_URL_H_
#define MESHWAVE_CLIENT_URL_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "meshwave/status.h"

namespace meshwave::client {

struct ServerUrl {
  bool tls = false;        // https or wss
  bool websocket = false;  // ws or wss
  std::string host;        // a name or an address (IPv6 without brackets)
  uint16_t port = 0;       // 80 or 443 when the URL names none
  // "http://host:port" (or https, ws, wss; IPv6 hosts in brackets).
  std::string ToString() const;
};

struct MeshUrl {
  ServerUrl server;
  std::string mesh_id;  // 12 lowercase hex digits
  // "/v1/meshes/{id}", the prefix of every request about the mesh.
  std::string Path() const;
  std::string ToString() const;
};

// Parses "http(s)://host[:port][/]" or "ws(s)://...". Safe on any input: a
// wrong scheme, user info, a query or fragment, an empty or malformed host,
// a port outside 1..65535 or a path give InvalidArgument naming the URL.
Result<ServerUrl> ParseServerUrl(std::string_view url);

// Parses "http(s)://host[:port]/v1/meshes/{id}[/]" (or ws, wss) with the
// checks above; the id must be 12 lowercase hex digits, as the server's ids
// are.
Result<MeshUrl> ParseMeshUrl(std::string_view url);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_URL_H_
