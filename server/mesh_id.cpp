#include "mesh_id.h"

#include <string>

#include "sha256.h"

namespace meshwave::server {

bool IsValidMeshId(std::string_view id) {
  if (id.size() != kMeshIdLength) return false;
  for (char c : id) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

std::string MeshIdFromSha256(std::string_view sha256_hex) {
  return std::string(sha256_hex.substr(0, kMeshIdLength));
}

std::string MeshIdOf(std::string_view original_digest, std::string_view settings,
                     std::string_view name) {
  std::string key = "meshwave-mesh 1\n";
  key.append(original_digest).append("\n").append(settings).append("\n").append(name);
  return MeshIdFromSha256(Sha256Hex(key));
}

}  // namespace meshwave::server
