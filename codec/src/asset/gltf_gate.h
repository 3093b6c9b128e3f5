// The checks a glTF document passes before tinygltf sees it. tinygltf 2.7
// trusts its input in ways an upload must not be trusted with (fuzzing and
// reading its source found each):
//  - its JSON-to-Value conversion (extras, extensions) recurses once per
//    nesting level: deep nesting overflows the stack. Here: a depth limit,
//    checked by nlohmann-json's iterative SAX parser first, with a limit
//    on the number of values (the parsed documents cost some 50 bytes per
//    value: "[0,0,0,..." amplifies 25-fold, and is parsed twice).
//  - in a .glb, every buffer without a uri gets its own copy of the BIN
//    chunk: a few bytes of JSON per buffer allocate gigabytes. Here: only
//    buffer 0 may use the BIN chunk, as glTF 2.0 says.
//  - it reads an image's bufferView without checking that the view lies
//    inside its buffer (a heap over-read). Here: every bufferView is checked
//    against the byteLength of its buffer.
//  - its file reads go through our callbacks; here each external buffer is
//    resolved in the file set once, with its size checked, so that a
//    missing, truncated or escaping .bin gets a message that says so.
// The checks mirror how tinygltf reads each value (an index that is not an
// integer is absent to it, a byteOffset that is not unsigned is 0), so that
// what passes here is what tinygltf then parses.
#ifndef MESHWAVE_ASSET_GLTF_GATE_H_
#define MESHWAVE_ASSET_GLTF_GATE_H_

#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "meshwave/file_set.h"
#include "meshwave/mesh_asset.h"
#include "meshwave/status.h"

namespace meshwave {

struct GltfGateResult {
  // External buffers by the name tinygltf will ask for (its decoding of the
  // URI) -> their bytes, resolved and read from the file set.
  std::map<std::string, std::string_view, std::less<>> buffer_files;
};

// `json`: the .gltf text or the GLB JSON chunk; `bin_size`: the GLB BIN
// chunk's size (has_bin false for .gltf or a GLB without one).
Result<GltfGateResult> CheckGltfDocument(std::string_view json, bool is_glb,
                                         bool has_bin, size_t bin_size,
                                         FileSet& files,
                                         std::string_view main_name,
                                         const AssetLimits& limits);

// glTF URIs are RFC 3986 references: percent-escapes decoded ("%20" is a
// space; '+' stays '+').
std::string DecodeUriPath(std::string_view uri);

// tinygltf's own decoding of a buffer URI (dlib's urldecode: also '+' ->
// ' '), to answer its file requests by the name it asks for.
std::string TinyGltfUrlDecode(std::string_view uri);

}  // namespace meshwave

#endif  // MESHWAVE_ASSET_GLTF_GATE_H_
