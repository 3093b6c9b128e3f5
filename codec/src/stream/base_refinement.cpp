#include "stream/base_refinement.h"

#include <cmath>

namespace meshwave {

size_t BaseRefinementBytes(uint32_t vertex_count) {
  return (3 * static_cast<size_t>(vertex_count) + 7) / 8;
}

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

Vec3 RefinedBasePosition(const StreamHeader::BaseMesh& base, const IntVec3& coarse,
                         const IntVec3& known, int missing) {
  const double middle = 0.5 * (std::ldexp(1.0, missing) - 1);
  Vec3 p;
  for (int a = 0; a < 3; ++a) {
    const int64_t fine = (coarse[a] << base.refinement_planes) + known[a];
    p[a] = base.origin[static_cast<size_t>(a)] +
           base.step * (static_cast<double>(fine) + middle);
  }
  return p;
}

}  // namespace meshwave
