#include "stream/base_refinement_encoder.h"

#include "stream/base_refinement.h"

namespace meshwave {

std::string EncodeBaseRefinementPlane(std::span<const IntVec3> residual, int plane) {
  std::string out(BaseRefinementBytes(static_cast<uint32_t>(residual.size())), '\0');
  for (size_t v = 0; v < residual.size(); ++v) {
    for (int a = 0; a < 3; ++a) {
      const size_t k = 3 * v + static_cast<size_t>(a);
      if ((residual[v][a] >> plane) & 1) out[k / 8] = static_cast<char>(out[k / 8] | (1 << (k % 8)));
    }
  }
  return out;
}

}  // namespace meshwave
