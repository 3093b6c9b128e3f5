#include "meshwave/mesh_id.h"

namespace meshwave {

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

}  // namespace meshwave
