// Fuzz target: the glTF reader (GLB parsing, the gate, tinygltf, accessors,
// the node tree, materials, image decoding) on arbitrary files. Byte 0
// even: the rest is a .glb; odd: the rest is split at kSeparator into a
// .gltf and the files it may name: m.bin, a.png, b.jpg, c.webp (in a memory
// file set). The reader promises a Status for every malformed input and an
// asset that satisfies RequireValidAsset.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "asset/asset_readers.h"
#include "asset_invariants_testonly.h"
#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"

namespace {
constexpr std::string_view kSeparator = "\n--file--\n";
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view input(reinterpret_cast<const char*>(data) + 1,
                               size - 1);
  meshwave::MemoryFileSet files;
  std::string main;
  if (data[0] % 2 == 0) {
    main = "m.glb";
    (void)files.Add(main, std::string(input));
  } else {
    main = "m.gltf";
    static constexpr const char* kNames[] = {"m.gltf", "m.bin", "a.png",
                                             "b.jpg", "c.webp"};
    const auto parts = meshwave::fuzz::SplitFiles(input, kSeparator);
    for (size_t i = 0; i < parts.size() && i < std::size(kNames); ++i) {
      (void)files.Add(kNames[i], std::string(parts[i]));
    }
  }
  const std::string_view bytes = *files.Read(main);
  const auto asset = meshwave::ParseGltfAsset(bytes, files, main,
                                              meshwave::fuzz::FuzzLimits());
  if (asset.ok()) meshwave::fuzz::RequireValidAsset(*asset);
  return 0;
}
