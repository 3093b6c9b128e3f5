// glTF 2.0 output of a triangle mesh (WriteMesh picks it for .glb and
// .gltf; the writer lives with the PLY and OBJ ones in mesh_writer.cpp).
#ifndef MESHWAVE_GLTF_H_
#define MESHWAVE_GLTF_H_

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "meshwave/mesh.h"
#include "meshwave/texture.h"

namespace meshwave {

enum class GltfForm {
  kBinary,    // .glb: the binary container, a JSON chunk and a BIN chunk
  kEmbedded,  // .gltf: JSON with the buffer as a base64 data URI
};

// The glTF form a path's extension asks for (.glb, .gltf; any case), or
// nullopt for any other extension.
std::optional<GltfForm> GltfFormFromPath(const std::filesystem::path& path);

// One scene, node and mesh of one indexed triangle primitive: POSITION as
// FLOAT VEC3 with min/max, indices UNSIGNED_INT, and with `colors` (linear
// RGB, one per vertex, clamped to [0, 1]) COLOR_0 as FLOAT VEC3. A mesh
// without faces gives an empty scene (glTF forbids empty buffers).
std::string SerializeGltf(const TriMesh& mesh, GltfForm form,
                          std::span<const Vec3> colors = {});

// The same with a texture (format version 9): one primitive of POSITION,
// TEXCOORD_0 (FLOAT VEC2), optional COLOR_0, with a normal map NORMAL and
// TANGENT (area-weighted normals, tangents along increasing u from the
// faces' UV gradients), and indices, and one material
// whose maps are `images` (at most one per role), embedded in the buffer
// (bufferViews with their mimeType), sampled with CLAMP_TO_EDGE and
// linear, mipmapped filtering. `corner_uvs` holds 6 floats a face (u0 v0
// u1 v1 u2 v2, ProgressiveDecoder::TextureCoordinates): a vertex whose
// corners have different UVs (along base-mesh edges, where the atlas cuts)
// is written once per UV. Without faces or images, or with corner_uvs not
// 6 per face, it writes what SerializeGltf writes.
std::string SerializeTexturedGltf(const TriMesh& mesh, GltfForm form,
                                  std::span<const float> corner_uvs,
                                  std::span<const TextureImage> images,
                                  const TextureMaterial& material,
                                  std::span<const Vec3> colors = {});
// How many vertices SerializeTexturedGltf writes for `mesh` (with images).
size_t TexturedVertexCount(const TriMesh& mesh, std::span<const float> corner_uvs);

}  // namespace meshwave

#endif  // MESHWAVE_GLTF_H_
