// Mesh ids: 12 hex digits, from what the mesh was made of (the server's
// MeshIdOf, server/mesh_identity.h) or, for a ready container ingested as
// it is, of the container's SHA-256; a re-encode keeps them. They come
// from URLs, so every use is preceded by IsValidMeshId; they never name a
// file (the catalog row holds the container path).
#ifndef MESHWAVE_MESH_ID_H_
#define MESHWAVE_MESH_ID_H_

#include <string>
#include <string_view>

namespace meshwave {

inline constexpr size_t kMeshIdLength = 12;

// Exactly 12 characters of [0-9a-f].
bool IsValidMeshId(std::string_view id);

// The id of a container with this SHA-256 (64 lowercase hex digits).
std::string MeshIdFromSha256(std::string_view sha256_hex);

}  // namespace meshwave

#endif  // MESHWAVE_MESH_ID_H_
