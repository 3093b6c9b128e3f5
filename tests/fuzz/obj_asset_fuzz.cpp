// Fuzz target: the OBJ + MTL reader on arbitrary files: the input split at
// kSeparator into m.obj, m.mtl and t.png (in a memory file set). The reader
// promises a Status for every malformed input and an asset that satisfies
// RequireValidAsset.
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
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  meshwave::MemoryFileSet files;
  static constexpr const char* kNames[] = {"m.obj", "m.mtl", "t.png"};
  const auto parts = meshwave::fuzz::SplitFiles(input, kSeparator);
  for (size_t i = 0; i < parts.size() && i < std::size(kNames); ++i) {
    (void)files.Add(kNames[i], std::string(parts[i]));
  }
  const std::string_view obj = *files.Read("m.obj");
  const auto asset = meshwave::ParseObjAsset(obj, files, "m.obj",
                                             meshwave::fuzz::FuzzLimits());
  if (asset.ok()) meshwave::fuzz::RequireValidAsset(*asset);
  return 0;
}
