// The decoder of the base mesh's connectivity (connectivity/gate_traversal.h).
#ifndef MESHWAVE_STREAM_BASE_CONNECTIVITY_DECODER_H_
#define MESHWAVE_STREAM_BASE_CONNECTIVITY_DECODER_H_

#include <cstdint>
#include <vector>

#include "entropy/arithmetic_decoder.h"
#include "meshwave/mesh.h"
#include "meshwave/status.h"

namespace meshwave {

// Reads `face_count` faces over `vertex_count` vertices. Safe on untrusted
// bytes: every index and every edge use is checked.
Result<std::vector<Face>> DecodeBaseConnectivity(ArithmeticDecoder& dec,
                                                 uint32_t vertex_count,
                                                 uint64_t face_count);

}  // namespace meshwave

#endif  // MESHWAVE_STREAM_BASE_CONNECTIVITY_DECODER_H_
