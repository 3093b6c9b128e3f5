// The read endpoints of /v1/meshes: listing, one mesh's description, its
// header, a progressive stream, single packets and the whole container.
// `id` arguments have passed IsValidMeshId.
#ifndef MESHWAVE_SERVER_MESH_HANDLERS_H_
#define MESHWAVE_SERVER_MESH_HANDLERS_H_

#include <string>

#include "meshwave/request_target.h"
#include "server_context.h"
#include "catalog_api.pb.h"
#include "slices_body.h"

namespace meshwave::server {

Response ListMeshes(ServerContext& ctx, const Request& req, const QueryParams& query);
Response DescribeMesh(ServerContext& ctx, const Request& req, const std::string& id);
Response GetHeader(ServerContext& ctx, const Request& req, const std::string& id);
Response GetStream(ServerContext& ctx, const Request& req, const std::string& id,
                   const QueryParams& query);
Response GetPacket(ServerContext& ctx, const Request& req, const std::string& id,
                   const std::string& packet);
Response GetContainer(ServerContext& ctx, const Request& req, const std::string& id);

// The catalog summary of an entry, as the API shows it.
void ToProto(const CatalogEntry& entry, proto::MeshSummary& out);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MESH_HANDLERS_H_
