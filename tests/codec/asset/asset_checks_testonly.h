// What the asset reader tests ask of a result: its error message, whether a
// note mentions something.
#ifndef MESHWAVE_TESTS_CODEC_ASSET_ASSET_CHECKS_TESTONLY_H_
#define MESHWAVE_TESTS_CODEC_ASSET_ASSET_CHECKS_TESTONLY_H_

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "meshwave/mesh_asset.h"

namespace meshwave::testing {

// Files beside the main one: name, bytes.
using ExtraFiles = std::vector<std::pair<std::string, std::string>>;

// The message of a failed read ("(ok)", and a test failure, if it read).
inline std::string ErrorOf(const Result<MeshAsset>& r) {
  EXPECT_FALSE(r.ok());
  return r.ok() ? std::string("(ok)") : r.status().message();
}

inline bool AnyNote(const MeshAsset& asset, const std::string& part) {
  for (const std::string& n : asset.notes) {
    if (n.find(part) != std::string::npos) return true;
  }
  return false;
}

// Reads `main_name` (bytes) with `others` beside it from a memory file set.
inline Result<MeshAsset> ParseInMemory(const std::string& main_name,
                                       const std::string& bytes,
                                       const ExtraFiles& others = {},
                                       const AssetLimits& limits = {}) {
  MemoryFileSet files;
  EXPECT_TRUE(files.Add(main_name, bytes).ok());
  for (const auto& [name, data] : others) {
    EXPECT_TRUE(files.Add(name, data).ok());
  }
  return ParseMeshAsset(files, main_name, limits);
}

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CODEC_ASSET_ASSET_CHECKS_TESTONLY_H_
