// Requests that continue a stream name the container their state belongs
// to (docs/API.md, "Re-encoded meshes"). After a re-encode the mesh is
// served from another container: a client holding packets of the old one
// must start over, never mix the two.
#ifndef MESHWAVE_SERVER_CONTAINER_PIN_H_
#define MESHWAVE_SERVER_CONTAINER_PIN_H_

#include <optional>
#include <string>

#include "catalog.h"

namespace meshwave::server {

// The message for the client when `pinned` names another container than the
// one `served` is served from; nullopt when it names this one or none.
std::optional<std::string> PinConflict(const CatalogEntry& served,
                                       const std::optional<std::string>& pinned);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_CONTAINER_PIN_H_
