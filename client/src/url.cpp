#include "meshwave/client/url.h"

#include <cctype>

namespace meshwave::client {
namespace {

Status Bad(std::string_view url, const std::string& why) {
  return InvalidArgument("URL \"" + std::string(url) + "\": " + why);
}

bool StartsWithNoCase(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i])
      return false;
  }
  return true;
}

bool IsHostChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.' ||
         c == '_';
}

// Splits the URL into server and path; `path` is what follows the authority.
Result<ServerUrl> ParseAuthority(std::string_view url, std::string_view& path) {
  ServerUrl s;
  std::string_view rest;
  if (StartsWithNoCase(url, "https://")) {
    s.tls = true;
    rest = url.substr(8);
  } else if (StartsWithNoCase(url, "http://")) {
    rest = url.substr(7);
  } else if (StartsWithNoCase(url, "wss://")) {
    s.tls = s.websocket = true;
    rest = url.substr(6);
  } else if (StartsWithNoCase(url, "ws://")) {
    s.websocket = true;
    rest = url.substr(5);
  } else {
    return Bad(url, "expected http://, https://, ws:// or wss://");
  }
  if (rest.find_first_of("?#") != std::string_view::npos) {
    return Bad(url, "a query or fragment is not allowed");
  }
  const size_t slash = rest.find('/');
  std::string_view authority = rest.substr(0, slash);
  path =
      slash == std::string_view::npos ? std::string_view() : rest.substr(slash);
  if (authority.find('@') != std::string_view::npos) {
    return Bad(url, "user information is not allowed");
  }
  std::string_view port_text;
  if (!authority.empty() && authority.front() == '[') {
    const size_t close = authority.find(']');
    if (close == std::string_view::npos)
      return Bad(url, "unclosed '[' in the host");
    s.host = std::string(authority.substr(1, close - 1));
    for (char c : s.host) {
      if (!std::isxdigit(static_cast<unsigned char>(c)) && c != ':' &&
          c != '.') {
        return Bad(url, "malformed IPv6 address");
      }
    }
    std::string_view after = authority.substr(close + 1);
    if (!after.empty()) {
      if (after.front() != ':') return Bad(url, "unexpected text after ']'");
      port_text = after.substr(1);
      if (port_text.empty()) return Bad(url, "empty port");
    }
  } else {
    const size_t colon = authority.find(':');
    s.host = std::string(authority.substr(0, colon));
    if (colon != std::string_view::npos) {
      port_text = authority.substr(colon + 1);
      if (port_text.empty()) return Bad(url, "empty port");
    }
    for (char c : s.host) {
      if (!IsHostChar(c)) return Bad(url, "invalid character in the host");
    }
  }
  if (s.host.empty()) return Bad(url, "no host");
  if (port_text.empty()) {
    s.port = s.tls ? 443 : 80;
  } else {
    uint32_t port = 0;
    if (port_text.size() > 5) return Bad(url, "port out of range");
    for (char c : port_text) {
      if (c < '0' || c > '9') return Bad(url, "port is not a number");
      port = port * 10 + static_cast<uint32_t>(c - '0');
    }
    if (port == 0 || port > 65535)
      return Bad(url, "port out of range (1..65535)");
    s.port = static_cast<uint16_t>(port);
  }
  return s;
}

bool IsMeshId(std::string_view id) {
  if (id.size() != 12) return false;
  for (char c : id) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace

std::string ServerUrl::ToString() const {
  const bool v6 = host.find(':') != std::string::npos;
  const char* scheme =
      websocket ? (tls ? "wss://" : "ws://") : (tls ? "https://" : "http://");
  return std::string(scheme) + (v6 ? "[" + host + "]" : host) + ":" +
         std::to_string(port);
}

std::string MeshUrl::Path() const { return "/v1/meshes/" + mesh_id; }

std::string MeshUrl::ToString() const { return server.ToString() + Path(); }

Result<ServerUrl> ParseServerUrl(std::string_view url) {
  std::string_view path;
  MW_ASSIGN_OR_RETURN(ServerUrl s, ParseAuthority(url, path));
  if (!path.empty() && path != "/") {
    return Bad(url, "expected a server URL without a path (http://host:port)");
  }
  return s;
}

Result<MeshUrl> ParseMeshUrl(std::string_view url) {
  std::string_view path;
  MW_ASSIGN_OR_RETURN(ServerUrl s, ParseAuthority(url, path));
  constexpr std::string_view kPrefix = "/v1/meshes/";
  if (path.substr(0, kPrefix.size()) != kPrefix) {
    return Bad(url, "expected a mesh URL, http://host:port/v1/meshes/{id}");
  }
  std::string_view id = path.substr(kPrefix.size());
  if (!id.empty() && id.back() == '/') id.remove_suffix(1);
  if (!IsMeshId(id)) {
    return Bad(url, "mesh id \"" + std::string(id) +
                        "\" is not 12 lowercase hex digits");
  }
  MeshUrl m;
  m.server = std::move(s);
  m.mesh_id = std::string(id);
  return m;
}

}  // namespace meshwave::client
