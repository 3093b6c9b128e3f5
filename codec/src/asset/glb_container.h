// The GLB container of binary glTF: a 12-byte header, a JSON chunk and an
// optional BIN chunk (glTF 2.0, section 4.4). Parsed here rather than by
// tinygltf for messages that say what is wrong (tinygltf says "Invalid glTF
// binary."): a truncated file names the length it declares and the length
// it has.
#ifndef MESHWAVE_ASSET_GLB_CONTAINER_H_
#define MESHWAVE_ASSET_GLB_CONTAINER_H_

#include <string_view>

#include "meshwave/status.h"

namespace meshwave {

struct GlbChunks {
  std::string_view json;
  std::string_view bin;  // empty when there is no BIN chunk
  bool has_bin = false;
};

bool LooksLikeGlb(std::string_view bytes);

// Splits a .glb into its chunks (views into `bytes`). ParseError naming
// `name` for a wrong magic or version, a truncated file, chunks that do not
// fit, a first chunk that is not JSON; chunks of unknown types after the
// BIN chunk are skipped, as the specification asks.
Result<GlbChunks> ParseGlb(std::string_view bytes, std::string_view name);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLB_CONTAINER_H_
