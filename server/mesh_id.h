// Mesh ids: 12 hex digits, from what the mesh was made of (MeshIdOf) or,
// for a ready container ingested as it is, of the container's SHA-256.
// They stay when the container is re-encoded. They come from URLs, so every use is preceded by IsValidMeshId; they never name a
// file (the catalog row holds the container path).
#ifndef MESHWAVE_SERVER_MESH_ID_H_
#define MESHWAVE_SERVER_MESH_ID_H_

#include <string>
#include <string_view>

namespace meshwave::server {

inline constexpr size_t kMeshIdLength = 12;

// Exactly 12 characters of [0-9a-f].
bool IsValidMeshId(std::string_view id);

// The first 12 of these 64 lowercase hex digits.
std::string MeshIdFromSha256(std::string_view sha256_hex);

// The id of a mesh made from the original `original_digest`
// (original_store.h) with the encoder settings `settings`
// (encode_settings.h) under the name `name`: the same upload, settings and
// name are the same mesh, whatever the container's format version, so a
// re-encode keeps the id.
std::string MeshIdOf(std::string_view original_digest, std::string_view settings,
                     std::string_view name);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_MESH_ID_H_
