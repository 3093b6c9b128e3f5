#include "mesh_identity.h"

#include "meshwave/mesh_id.h"
#include "sha256.h"

namespace meshwave::server {

std::string MeshIdOf(std::string_view original_digest, std::string_view settings,
                     std::string_view name) {
  std::string key = "meshwave-mesh 1\n";
  key.append(original_digest).append("\n").append(settings).append("\n").append(name);
  return MeshIdFromSha256(Sha256Hex(key));
}

}  // namespace meshwave::server
