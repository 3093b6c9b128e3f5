// Which mesh an ingest makes: the same upload, encoder settings and name
// are the same mesh, whatever the container's format version, so a
// re-encode keeps the id and a repeated upload is found before encoding.
#ifndef MESHWAVE_SERVER_MESH_IDENTITY_H_
#define MESHWAVE_SERVER_MESH_IDENTITY_H_

#include <string>
#include <string_view>

namespace meshwave::server {

// The id (meshwave/mesh_id.h) of a mesh made from the original
// `original_digest` (original_store.h) with the encoder settings `settings`
// (encode_settings.h) under the name `name`.
std::string MeshIdOf(std::string_view original_digest, std::string_view settings,
                     std::string_view name);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MESH_IDENTITY_H_
