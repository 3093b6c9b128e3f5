#include "meshwave/mesh_id.h"

namespace meshwave {
namespace {

bool IsLowerHex(std::string_view text, size_t length) {
  if (text.size() != length) return false;
  for (char c : text) {
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  }
  return true;
}

}  // namespace

bool IsValidMeshId(std::string_view id) { return IsLowerHex(id, kMeshIdLength); }

bool IsValidContainerDigest(std::string_view digest) {
  return IsLowerHex(digest, kContainerDigestLength);
}

std::string MeshIdFromSha256(std::string_view sha256_hex) {
  return std::string(sha256_hex.substr(0, kMeshIdLength));
}

}  // namespace meshwave
