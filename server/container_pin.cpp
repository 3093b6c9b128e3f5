#include "container_pin.h"

namespace meshwave::server {

std::optional<std::string> PinConflict(const CatalogEntry& served,
                                       const std::optional<std::string>& pinned) {
  if (!pinned || *pinned == served.sha256) return std::nullopt;
  return "mesh " + served.id + " was re-encoded: it is now served from container " +
         served.sha256 + ", and what you hold belongs to container " + *pinned +
         "; start over from its header";
}

}  // namespace meshwave::server
