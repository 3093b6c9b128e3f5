#include "stream/base_refinement.h"

#include <cmath>

namespace meshwave {

size_t BaseRefinementBytes(uint32_t vertex_count) {
  return (3 * static_cast<size_t>(vertex_count) + 7) / 8;
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
