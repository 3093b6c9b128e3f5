// Fuzz target: one mesh reader (PLY, OBJ or OFF, chosen at build time by
// MESHWAVE_FUZZ_FORMAT) on arbitrary bytes. The readers promise a Status
// for every malformed input, no allocation sized by an unchecked count, and
// a mesh whose indices are in range when they succeed.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_fixture_testonly.h"
#include "meshwave/mesh.h"
#include "meshwave/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  auto mesh = meshwave::ParseMesh(bytes, meshwave::MeshFormat::MESHWAVE_FUZZ_FORMAT, "fuzz");
  if (!mesh.ok()) return 0;
  meshwave::fuzz::Require(!mesh->positions.empty() && !mesh->faces.empty(),
                          "a parsed mesh is not empty");
  for (const auto& f : mesh->faces) {
    for (uint32_t v : f) {
      meshwave::fuzz::Require(v < mesh->positions.size(), "face indices are in range");
    }
  }
  for (const auto& p : mesh->positions) {
    meshwave::fuzz::Require(p.allFinite(), "coordinates are finite");
  }
  return 0;
}
