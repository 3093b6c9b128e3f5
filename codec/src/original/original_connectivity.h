// The original layer's connectivity code (docs/FORMAT.md 2.5): the input
// mesh's faces over its own vertex ids, whatever they are (several
// components, boundaries, non-manifold edges, repeated or degenerate
// faces, vertices in no face), and the traversal its positions follow.
#ifndef MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_H_
#define MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_H_

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "meshwave/mesh.h"
#include "meshwave/status.h"
#include "original/original_traversal.h"

namespace meshwave::original {

// Codes `faces` (ids < vertex_count) into one payload; `traversal` gets the
// order both sides will use. Errors only for ids out of range.
Result<std::string> EncodeConnectivity(uint32_t vertex_count, const std::vector<Face>& faces,
                                       Traversal* traversal);

// Decodes a payload of EncodeConnectivity given the counts the header
// announces. Untrusted bytes: any damage is a kParseError naming the face.
Result<Traversal> DecodeConnectivity(std::string_view payload, uint32_t vertex_count,
                                     uint64_t face_count);

}  // namespace meshwave::original

#endif  // MESHWAVE_ORIGINAL_ORIGINAL_CONNECTIVITY_H_
