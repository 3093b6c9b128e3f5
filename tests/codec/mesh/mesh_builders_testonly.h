// Test-only helpers: small meshes and binary PLY bytes built in code.
#ifndef MESHWAVE_TESTS_CODEC_MESH_MESH_BUILDERS_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_MESH_MESH_BUILDERS_TESTONLY_H_

#include <bit>
#include <cstring>
#include <string>

#include "core/byte_reader.h"
#include "meshwave/mesh.h"

namespace meshwave::testing {

// Appends `value` to `out` in byte order `order`.
template <class T>
void AppendBinary(std::string& out, T value, std::endian order) {
  if (order != std::endian::native) value = ByteSwapped(value);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

// A regular tetrahedron-like closed mesh: 4 vertices, 4 outward faces.
inline TriMesh Tetrahedron() {
  TriMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  mesh.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return mesh;
}

// An n-by-n grid of unit squares split into triangles: an open disc.
inline TriMesh Grid(uint32_t n) {
  TriMesh mesh;
  for (uint32_t y = 0; y <= n; ++y) {
    for (uint32_t x = 0; x <= n; ++x) mesh.positions.emplace_back(x, y, 0.0);
  }
  auto at = [n](uint32_t x, uint32_t y) { return y * (n + 1) + x; };
  for (uint32_t y = 0; y < n; ++y) {
    for (uint32_t x = 0; x < n; ++x) {
      mesh.faces.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
      mesh.faces.push_back({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
    }
  }
  return mesh;
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_MESH_MESH_BUILDERS_TESTONLY_H_
