// glTF 2.0 output of a triangle mesh (WriteMesh picks it for .glb and
// .gltf; the writer lives with the PLY and OBJ ones in mesh_writer.cpp).
#ifndef MESHWAVE_GLTF_H_
#define MESHWAVE_GLTF_H_

#include <filesystem>
#include <optional>
#include <string>

#include "meshwave/mesh.h"

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

}  // namespace meshwave

#endif  // MESHWAVE_GLTF_H_
