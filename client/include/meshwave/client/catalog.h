// The meshes a server hosts (GET /v1/meshes, as protobuf), all pages.
#ifndef MESHWAVE_CLIENT_CATALOG_H_
#define MESHWAVE_CLIENT_CATALOG_H_

#include "catalog_api.pb.h"
#include "meshwave/client/transport.h"
#include "meshwave/client/url.h"
#include "meshwave/status.h"

namespace meshwave::client {

// Blocking: runs its own io_context on the calling thread. Errors as the
// transport's; a listing that does not parse is kParseError.
Result<proto::MeshList> ListCatalog(const ServerUrl& server,
                                    const TransportOptions& options);

}  // namespace meshwave::client

#endif  // MESHWAVE_CLIENT_CATALOG_H_
