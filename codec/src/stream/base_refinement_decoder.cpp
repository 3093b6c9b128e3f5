#include "stream/base_refinement_decoder.h"

#include <string>

#include "stream/base_refinement.h"

namespace meshwave {

Status DecodeBaseRefinementPlane(std::string_view payload, int plane,
                                 std::vector<IntVec3>& known) {
  if (payload.size() != BaseRefinementBytes(static_cast<uint32_t>(known.size()))) {
    return ParseError("base refinement: " + std::to_string(payload.size()) + " bytes for " +
                      std::to_string(known.size()) + " vertices");
  }
  for (size_t v = 0; v < known.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const size_t k = 3 * v + static_cast<size_t>(a);
      const int64_t bit = (static_cast<uint8_t>(payload[k / 8]) >> (k % 8)) & 1;
      known[v][a] |= bit << plane;
    }
  }
  return Status::Ok();
}

}  // namespace meshwave
